#include "export/frames/channel_image.h"

#include <algorithm>
#include <string>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "render/maps/gbuffer_maps.h"

namespace goris {

namespace {

Error missing(Channel c, const std::string& why) {
  return Error(std::string("channel '") + channel_info(c).id + "'", why);
}

// Planar RGB from an interleaved RGB image (what gbuffer_maps.h writes).
std::vector<float> planar(const Image& img) {
  const std::vector<float> px = img.pixels.to_host();
  const size_t hw = img.pixel_count();
  std::vector<float> out(3 * hw);
  for (size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) out[size_t(c) * hw + p] = px[3 * p + size_t(c)];
  return out;
}

std::vector<float> grey(const float* plane, size_t hw) {
  std::vector<float> out(3 * hw);
  for (int c = 0; c < 3; ++c)
    for (size_t p = 0; p < hw; ++p) out[size_t(c) * hw + p] = std::clamp(plane[p], 0.0f, 1.0f);
  return out;
}

std::vector<float> clamped(const std::vector<float>& rgb, Channel c, size_t hw) {
  if (rgb.size() != 3 * hw) throw missing(c, "the render holds no such image");
  std::vector<float> out(rgb);
  for (float& v : out) v = std::clamp(v, 0.0f, 1.0f);
  return out;
}

}  // namespace

std::vector<float> channel_image(Channel c, const GBuffer& gb, const IntrinsicMaps* maps) {
  const int w = gb.width, h = gb.height;
  const size_t hw = gb.pixels();
  if (channel_info(c).needs == ChannelNeeds::RemovalMasks)
    throw missing(c, "the removal's masks are files of the training views (RUN/removal/), not a render");
  if ((channel_info(c).needs == ChannelNeeds::Intrinsic || channel_info(c).needs == ChannelNeeds::ScreenFilter) && !maps)
    throw missing(c, "needs an intrinsic run (train with mode intrinsic or auto)");
  const std::vector<float> alpha = gb.alpha.to_host();
  // The screen-space filter's own images: empty without the filter.
  auto filtered = [&](const std::vector<float>& v, size_t size) -> const std::vector<float>& {
    if (v.size() != size) throw missing(c, "needs the screen-space filter (intrinsic_screen_space_filter)");
    return v;
  };
  auto extra_plane = [&](int first, int count) {
    if (gb.n_extras != extra::kCount) throw missing(c, "the model has no material channels");
    const std::vector<float> e = gb.extras.to_host();
    return std::vector<float>(e.begin() + std::ptrdiff_t(size_t(first) * hw),
                              e.begin() + std::ptrdiff_t(size_t(first + count) * hw));
  };
  switch (c) {
    case Channel::Final:
      return clamped(maps ? maps->color : gb.color.to_host(), c, hw);
    case Channel::Diffuse:
      return clamped(extra_plane(extra::kDiffuse, 3), c, hw);
    case Channel::Fresnel:
      return clamped(extra_plane(extra::kFresnel, 3), c, hw);
    case Channel::Roughness:
      return grey(extra_plane(extra::kRoughness, 1).data(), hw);
    case Channel::Region:
      return grey(extra_plane(extra::kRegion, 1).data(), hw);
    case Channel::Label:
      return grey(extra_plane(extra::kLabel, 1).data(), hw);
    case Channel::Alpha:
      return grey(alpha.data(), hw);
    case Channel::Normal:
      return planar(normals_to_rgb(gb.normal.to_host().data(), alpha.data(), w, h));
    case Channel::Depth:
      return planar(depth_to_turbo(gb.depth.to_host().data(), alpha.data(), w, h, /*depth_is_weighted=*/true));
    case Channel::Glossy:
      return clamped(maps->glossy, c, hw);
    case Channel::IndirectLight:
      return clamped(maps->indirect, c, hw);
    case Channel::EnvLight:
      return clamped(maps->env, c, hw);
    case Channel::Visibility:
      if (maps->visibility.size() != hw) throw missing(c, "the render holds no visibility");
      return grey(maps->visibility.data(), hw);
    case Channel::ScreenRoughness:
      return grey(filtered(maps->screen_roughness, hw).data(), hw);
    case Channel::TracedIndirect:
      return clamped(filtered(maps->indirect_traced, 3 * hw), c, hw);
    case Channel::TracedVisibility:
      return grey(filtered(maps->visibility_traced, hw).data(), hw);
    case Channel::LightingMask:
    case Channel::InpaintMask:
      break;
  }
  throw missing(c, "not a rendered channel");
}

}  // namespace goris
