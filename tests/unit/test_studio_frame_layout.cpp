// The CUDA frame layout, run on the CPU: the planar -> interleaved passes (3-channel maps padded to 4 for
// CUDA-GL interop), a device-layout frame equal to the host frame channel by channel, the selection and
// intrinsic maps on such a frame, and which upload path a frame's images take.
#include <random>
#include <vector>

#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_studio_scenes.h"
#include "ui/display/display_frame.h"
#include "ui/display/frame_layout.h"
#include "ui/display/frame_textures.h"

using namespace goris;
using namespace goris::ui;

namespace {

GaussianModel wall(int n = 120) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  GaussianModel m(Device::CPU);
  m.allocate(size_t(n));
  for (int i = 0; i < n; ++i) {
    test::set_studio_gaussian(m, i, glm::vec3(1.2f * u(rng), 1.0f * u(rng), 0.05f * u(rng)),
                              glm::vec3(0.25f, 0.25f, 0.02f), glm::vec3(u(rng), u(rng), u(rng)));
    for (int k = 0; k < extra::kCount; ++k) m.values(Param::ExtraLogit)[i * extra::kCount + k] = 2.0f * u(rng);
  }
  return m;
}

// Host image [H][W][hc] against the device-layout image [H][W][dc] (dc >= hc: the rest padded with `pad`).
void expect_same_image(const std::vector<float>& host, int hc, const Buffer<float>& device, int dc, float pad,
                       const char* what) {
  ASSERT_EQ(device.device(), Device::CPU);
  ASSERT_EQ(host.size() / size_t(hc), device.size() / size_t(dc)) << what;
  const size_t hw = host.size() / size_t(hc);
  for (size_t p = 0; p < hw; ++p) {
    for (int c = 0; c < hc; ++c)
      ASSERT_EQ(device[p * dc + c], host[p * hc + c]) << what << " pixel " << p << " c " << c;
    for (int c = hc; c < dc; ++c) ASSERT_EQ(device[p * dc + c], pad) << what << " pixel " << p << " padding";
  }
}

}  // namespace

TEST(StudioFrameLayout, PassesOnTheCpu) {
  EXPECT_EQ(frame_layout::interop_channels(1), 1);
  EXPECT_EQ(frame_layout::interop_channels(2), 2);
  EXPECT_EQ(frame_layout::interop_channels(3), 4);
  EXPECT_EQ(frame_layout::interop_channels(4), 4);

  // Two pixels, planar channels [C][2].
  const std::vector<float> planar = {1, 2, 3, 4, 5, 6, 7, 8};  // c0 = (1,2), c1 = (3,4), c2 = (5,6), c3 = (7,8)
  std::vector<float> out(2 * 4, -1.0f);
  frame_layout::interleave(Device::CPU, planar.data(), 1, 3, 2, out.data(), 4, 0);
  frame_layout::fill(Device::CPU, out.data(), 2, 4, 3, 1.0f);
  EXPECT_EQ(out, (std::vector<float>{3, 5, 7, 1, 4, 6, 8, 1}));
  frame_layout::interleave(Device::CPU, planar.data(), 0, 1, 2, out.data(), 4, 2);
  EXPECT_EQ(out, (std::vector<float>{3, 5, 1, 1, 4, 6, 2, 1}));

  // Normals: unit where alpha is high enough and the normal not null, else 0; the 4th column untouched.
  const std::vector<float> normal = {3, 0, 3, 0, 0, 0, 4, 0, 4};  // pixel 0 (3,0,4), 1 (0,0,0), 2 (3,0,4)
  const std::vector<float> alpha = {0.5f, 0.9f, 0.01f};
  std::vector<float> n(3 * 4, 9.0f);
  frame_layout::unit_normals(Device::CPU, normal.data(), alpha.data(), 3, DisplayFrame::kMinAlpha, n.data(), 4);
  EXPECT_EQ(n, (std::vector<float>{0.6f, 0, 0.8f, 9, 0, 0, 0, 9, 0, 0, 0, 9}));

  const std::vector<float> coverage = {-0.5f, 0.25f, 1.5f};
  std::vector<float> clamped(3);
  frame_layout::clamp_unit(Device::CPU, coverage.data(), 3, clamped.data());
  EXPECT_EQ(clamped, (std::vector<float>{0, 0.25f, 1}));
}

// What make_display_frame does for a CUDA G-buffer, run on a CPU one: the same numbers as the host frame.
TEST(StudioFrameLayout, DeviceFrameEqualsTheHostFrame) {
  GaussianModel m = wall();
  const Camera cam = test::studio_front_camera();
  const RasterOutput out = rasterize(m.view(true), cam, RasterSettings{}, Device::CPU);
  const DisplayFrame h = make_display_frame(out.gbuffer, cam);
  const DisplayFrame d = make_device_display_frame(out.gbuffer, cam);
  EXPECT_FALSE(h.gpu.any());
  ASSERT_TRUE(d.gpu.any());
  EXPECT_EQ(d.width, h.width);
  EXPECT_EQ(d.height, h.height);
  // Nothing of the images on the host but what the GUI reads there.
  for (const std::vector<float>* v : {&d.color, &d.normal, &d.diffuse, &d.fresnel, &d.misc, &d.selection})
    EXPECT_TRUE(v->empty());
  expect_same_image(h.color, 3, d.gpu.color, 4, 1.0f, "color");
  expect_same_image(h.normal, 3, d.gpu.normal, 4, 1.0f, "normal");
  expect_same_image(h.diffuse, 3, d.gpu.diffuse, 4, 1.0f, "diffuse");
  expect_same_image(h.fresnel, 3, d.gpu.fresnel, 4, 1.0f, "fresnel");
  expect_same_image(h.misc, 4, d.gpu.misc, 4, 0.0f, "misc");
  EXPECT_EQ(d.depth, h.depth);
  EXPECT_EQ(d.alpha, h.alpha);
  EXPECT_EQ(d.inv_depth_near, h.inv_depth_near);
  EXPECT_EQ(d.inv_depth_far, h.inv_depth_far);
  EXPECT_FALSE(d.intrinsic());
  EXPECT_FALSE(d.has_selection());
  // Picking reads only host data, so it answers the same on both.
  for (const glm::vec2 uv : {glm::vec2(30.5f, 17.5f), glm::vec2(2.5f, 2.5f), glm::vec2(47.9f, 39.9f)}) {
    const auto a = pick(h, uv.x, uv.y), b = pick(d, uv.x, uv.y);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->hit, b->hit);
    EXPECT_EQ(a->alpha, b->alpha);
    EXPECT_EQ(a->depth, b->depth);
    EXPECT_EQ(a->world, b->world);
  }

  // Without extras the material maps are zero (alpha still in misc).
  const RasterOutput plain = rasterize(m.view(false), cam, RasterSettings{}, Device::CPU);
  ASSERT_LT(plain.gbuffer.n_extras, extra::kCount);
  const DisplayFrame hp = make_display_frame(plain.gbuffer, cam), dp = make_device_display_frame(plain.gbuffer, cam);
  expect_same_image(hp.diffuse, 3, dp.gpu.diffuse, 4, 1.0f, "diffuse without extras");
  expect_same_image(hp.misc, 4, dp.gpu.misc, 4, 0.0f, "misc without extras");
}

TEST(StudioFrameLayout, SelectionAndIntrinsicMapsOnADeviceFrame) {
  GaussianModel m = wall(40);
  const Camera cam = test::studio_front_camera();
  const RasterOutput out = rasterize(m.view(true), cam, RasterSettings{}, Device::CPU);
  DisplayFrame d = make_device_display_frame(out.gbuffer, cam);
  DisplayFrame h = make_display_frame(out.gbuffer, cam);
  const size_t hw = d.pixels();

  // The coverage stays with the images: on the device for a device frame, on the host for a host frame.
  std::vector<float> cov(hw);
  for (size_t p = 0; p < hw; ++p) cov[p] = float(p % 7) * 0.3f - 0.4f;
  const Buffer<float> coverage(cov, Device::CPU);
  add_selection_coverage(d, coverage);
  add_selection_coverage(h, coverage);
  EXPECT_TRUE(d.selection.empty());
  ASSERT_EQ(d.gpu.selection.size(), hw);
  ASSERT_EQ(h.selection.size(), hw);
  EXPECT_TRUE(d.has_selection());
  EXPECT_TRUE(h.has_selection());
  for (size_t p = 0; p < hw; ++p) {
    EXPECT_EQ(d.gpu.selection[p], h.selection[p]);
    EXPECT_GE(h.selection[p], 0.0f);
    EXPECT_LE(h.selection[p], 1.0f);
  }
  EXPECT_THROW(add_selection_coverage(d, Buffer<float>(std::vector<float>(hw + 1), Device::CPU)), Error);

  // Intrinsic maps are host images: the shaded colour replaces the device colour on the host.
  IntrinsicMaps maps;
  maps.width = d.width;
  maps.height = d.height;
  for (std::vector<float>* v : {&maps.color, &maps.glossy, &maps.indirect, &maps.env}) v->assign(3 * hw, 0.0f);
  maps.visibility.assign(hw, 0.5f);
  for (size_t i = 0; i < 3 * hw; ++i) maps.color[i] = float(i) / float(3 * hw);
  add_intrinsic_maps(d, maps);
  EXPECT_TRUE(d.gpu.color.empty());
  ASSERT_EQ(d.color.size(), 3 * hw);
  const size_t p = 17 * 48 + 30;
  for (int c = 0; c < 3; ++c) EXPECT_EQ(d.color[p * 3 + c], maps.color[c * hw + p]);
  EXPECT_TRUE(d.intrinsic());
  EXPECT_FALSE(d.gpu.normal.empty());  // the G-buffer's own maps stay on the device
  maps.width += 1;
  EXPECT_THROW(add_intrinsic_maps(d, maps), Error);
}

TEST(StudioFrameLayout, UploadPathFollowsWhereTheImageIs) {
  for (bool compiled : {false, true})
    for (bool failed : {false, true}) EXPECT_EQ(upload_path(Device::CPU, compiled, failed), UploadPath::Host);
  EXPECT_EQ(upload_path(Device::CUDA, true, false), UploadPath::Interop);
  EXPECT_EQ(upload_path(Device::CUDA, true, true), UploadPath::DeviceToHost);  // interop failed once: no retry
  EXPECT_EQ(upload_path(Device::CUDA, false, false), UploadPath::DeviceToHost);
}

TEST(StudioFrameLayout, CpuOnlyBuildNamesTheDisplay) {
  if (cuda_compiled()) GTEST_SKIP() << "this build has the CUDA backend";
  float out[4] = {};
  test::expect_error([&] { frame_layout::fill(Device::CUDA, out, 1, 4, 0, 1.0f); },
                     "display: CUDA device requested but this build has no CUDA backend");
}
