// export/frames/channel_image.h: every channel of a hand-made G-buffer (two pixels: one covered, one empty)
// comes out as the editor colours it, and the channels a render cannot hold are refused by name.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "export/frames/channel_image.h"

using namespace goris;

namespace {

constexpr int W = 2, H = 1;
constexpr size_t HW = size_t(W) * H;

GBuffer two_pixels() {
  GBuffer g;
  g.width = W;
  g.height = H;
  g.n_extras = extra::kCount;
  g.color = Buffer<float>(std::vector<float>{1.5f, 0.0f, 0.25f, 0.0f, -0.5f, 0.0f}, Device::CPU);
  g.alpha = Buffer<float>(std::vector<float>{1.0f, 0.0f}, Device::CPU);
  g.depth = Buffer<float>(std::vector<float>{2.0f, 0.0f}, Device::CPU);
  g.median_depth = Buffer<float>(std::vector<float>{2.0f, 0.0f}, Device::CPU);
  g.normal = Buffer<float>(std::vector<float>{0.0f, 0.0f, 0.0f, 0.0f, -2.0f, 0.0f}, Device::CPU);  // (0, 0, -2)
  std::vector<float> e(size_t(extra::kCount) * HW, 0.0f);
  auto set = [&](int ch, float v) { e[size_t(ch) * HW] = v; };
  set(extra::kDiffuse + 0, 0.2f), set(extra::kDiffuse + 1, 0.4f), set(extra::kDiffuse + 2, 0.6f);
  set(extra::kFresnel + 0, 0.04f), set(extra::kFresnel + 1, 0.05f), set(extra::kFresnel + 2, 0.06f);
  set(extra::kRoughness, 0.7f), set(extra::kRegion, 0.3f), set(extra::kLabel, 1.0f);
  g.extras = Buffer<float>(e, Device::CPU);
  return g;
}

IntrinsicMaps maps_of_two_pixels(bool screen_filter) {
  IntrinsicMaps m;
  m.width = W;
  m.height = H;
  m.color = {0.9f, 0.0f, 0.8f, 0.0f, 0.7f, 0.0f};
  m.sh_color = m.color;
  m.glossy = {0.1f, 0.0f, 2.0f, 0.0f, 0.3f, 0.0f};  // 2 is clamped to 1
  m.indirect = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  m.visibility = {0.25f, 1.0f};
  m.env = {0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f};
  if (screen_filter) {
    m.screen_roughness = {0.6f, 0.0f};
    m.indirect_traced = m.indirect;
    m.visibility_traced = m.visibility;
  }
  return m;
}

// The covered pixel's (r, g, b).
std::vector<float> first(const std::vector<float>& rgb) { return {rgb[0], rgb[HW], rgb[2 * HW]}; }

std::string error_of(Channel c, const GBuffer& g, const IntrinsicMaps* m) {
  try {
    channel_image(c, g, m);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(ChannelImage, MaterialsGeometryAndLightAsTheViewportsShowThem) {
  const GBuffer g = two_pixels();
  const IntrinsicMaps m = maps_of_two_pixels(true);
  auto near = [](const std::vector<float>& a, std::vector<float> b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-6f) << i;
  };
  near(channel_image(Channel::Final, g, nullptr), {1.0f, 0.0f, 0.25f, 0.0f, 0.0f, 0.0f});  // clamped to [0, 1]
  near(first(channel_image(Channel::Final, g, &m)), {0.9f, 0.8f, 0.7f});  // intrinsic: the shaded C
  near(first(channel_image(Channel::Diffuse, g, nullptr)), {0.2f, 0.4f, 0.6f});
  near(first(channel_image(Channel::Fresnel, g, nullptr)), {0.04f, 0.05f, 0.06f});
  near(channel_image(Channel::Roughness, g, nullptr), {0.7f, 0.0f, 0.7f, 0.0f, 0.7f, 0.0f});  // grey
  near(first(channel_image(Channel::Region, g, nullptr)), {0.3f, 0.3f, 0.3f});
  near(first(channel_image(Channel::Label, g, nullptr)), {1.0f, 1.0f, 1.0f});
  near(channel_image(Channel::Alpha, g, nullptr), {1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f});
  // Normal (0, 0, -2) -> normalised * 0.5 + 0.5 = (0.5, 0.5, 0); the empty pixel is black.
  const std::vector<float> n = channel_image(Channel::Normal, g, nullptr);
  EXPECT_NEAR(n[0], 0.5f, 2.0f / 255.0f);
  EXPECT_NEAR(n[HW], 0.5f, 2.0f / 255.0f);
  EXPECT_NEAR(n[2 * HW], 0.0f, 1e-6f);
  EXPECT_EQ(n[1] + n[HW + 1] + n[2 * HW + 1], 0.0f);
  // Depth through TURBO: the covered pixel has a colour, the empty one none.
  const std::vector<float> d = channel_image(Channel::Depth, g, nullptr);
  EXPECT_GT(d[0] + d[HW] + d[2 * HW], 0.1f);
  EXPECT_EQ(d[1] + d[HW + 1] + d[2 * HW + 1], 0.0f);
  near(first(channel_image(Channel::Glossy, g, &m)), {0.1f, 1.0f, 0.3f});
  near(first(channel_image(Channel::IndirectLight, g, &m)), {0.5f, 0.5f, 0.5f});
  near(first(channel_image(Channel::EnvLight, g, &m)), {0.3f, 0.3f, 0.3f});
  near(first(channel_image(Channel::Visibility, g, &m)), {0.25f, 0.25f, 0.25f});
  near(first(channel_image(Channel::ScreenRoughness, g, &m)), {0.6f, 0.6f, 0.6f});
  near(first(channel_image(Channel::TracedIndirect, g, &m)), {0.5f, 0.5f, 0.5f});
  near(first(channel_image(Channel::TracedVisibility, g, &m)), {0.25f, 0.25f, 0.25f});
}

TEST(ChannelImage, EveryChannelIsAnImageOrRefusedByName) {
  const GBuffer g = two_pixels();
  const IntrinsicMaps m = maps_of_two_pixels(true), unfiltered = maps_of_two_pixels(false);
  GBuffer bare = two_pixels();
  bare.n_extras = 0;
  bare.extras = Buffer<float>();
  for (const ChannelInfo& c : all_channels()) {
    SCOPED_TRACE(c.id);
    const std::string name = std::string("channel '") + c.id + "'";
    if (c.needs == ChannelNeeds::RemovalMasks) {
      const std::string e = error_of(c.channel, g, &m);
      EXPECT_NE(e.find(name), std::string::npos) << e;
      EXPECT_NE(e.find("not a render"), std::string::npos) << e;
      continue;
    }
    EXPECT_EQ(channel_image(c.channel, g, &m).size(), 3 * HW);
    if (c.needs == ChannelNeeds::Model) {
      EXPECT_EQ(channel_image(c.channel, g, nullptr).size(), 3 * HW);
    } else {
      const std::string e = error_of(c.channel, g, nullptr);
      EXPECT_NE(e.find("needs an intrinsic run"), std::string::npos) << e;
    }
    if (c.needs == ChannelNeeds::ScreenFilter) {
      const std::string e = error_of(c.channel, g, &unfiltered);
      EXPECT_NE(e.find("screen-space filter"), std::string::npos) << e;
    }
  }
  const std::string e = error_of(Channel::Fresnel, bare, nullptr);
  EXPECT_NE(e.find("no material channels"), std::string::npos) << e;
}
