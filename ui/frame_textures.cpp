#include "ui/frame_textures.h"

#include <opencv2/imgproc.hpp>
#include <vector>

namespace goris::ui {

bool FrameTextures::has(Channel c) const {
  if (!has_frame()) return false;
  switch (channel_info(c).needs) {
    case ChannelNeeds::Model:
      return true;
    case ChannelNeeds::Intrinsic:
      return has_intrinsic;
    case ChannelNeeds::ScreenFilter:
      return has_intrinsic && has_screen_roughness;
    case ChannelNeeds::RemovalMasks:
      return c == Channel::LightingMask ? has_lighting_mask : has_inpaint_mask;
  }
  return false;
}

void FrameTextures::upload(const DisplayFrame& f) {
  color.upload(f.width, f.height, 3, f.color.data());
  normal.upload(f.width, f.height, 3, f.normal.data());
  diffuse.upload(f.width, f.height, 3, f.diffuse.data());
  fresnel.upload(f.width, f.height, 3, f.fresnel.data());
  misc.upload(f.width, f.height, 4, f.misc.data());
  depth.upload(f.width, f.height, 1, f.depth.data());
  has_intrinsic = f.intrinsic();
  has_screen_roughness = has_intrinsic && f.screen_roughness;
  if (has_intrinsic) {
    glossy.upload(f.width, f.height, 3, f.glossy.data());
    indirect.upload(f.width, f.height, 3, f.indirect.data());
    env.upload(f.width, f.height, 3, f.env.data());
    light.upload(f.width, f.height, 2, f.light.data());
  }
  has_selection = !f.selection.empty();
  if (has_selection) selection.upload(f.width, f.height, 1, f.selection.data());
  width = f.width;
  height = f.height;
  inv_depth_near = f.inv_depth_near;
  inv_depth_far = f.inv_depth_far;
  indirect_gain = f.indirect_gain;
  frame_id = f.id;
  ++version;
}

void FrameTextures::upload_photo(const Image& rgb) {
  const std::vector<float> px = rgb.pixels.to_host();
  photo.upload(rgb.width, rgb.height, rgb.channels, px.data());
  ++version;
}

void FrameTextures::upload_masks(const std::string& key, const Image* lighting, const Image* inpaint) {
  masks_key = key;
  has_lighting_mask = lighting != nullptr;
  has_inpaint_mask = inpaint != nullptr;
  for (auto [im, tex] : {std::pair{lighting, &lighting_mask}, std::pair{inpaint, &inpaint_mask}}) {
    if (!im) continue;
    const std::vector<float> px = im->pixels.to_host();
    tex->upload(im->width, im->height, im->channels, px.data());
  }
  ++version;
}

void FrameTextures::create_turbo_table() {
  // OpenCV's table, as goris::depth_to_turbo uses it (render/maps/gbuffer_maps.cpp).
  cv::Mat ramp(1, 256, CV_8UC1), bgr;
  for (int i = 0; i < 256; ++i) ramp.at<uint8_t>(0, i) = uint8_t(i);
  cv::applyColorMap(ramp, bgr, cv::COLORMAP_TURBO);
  std::vector<float> rgb(256 * 3);
  for (int i = 0; i < 256; ++i) {
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, i);
    for (int k = 0; k < 3; ++k) rgb[size_t(i) * 3 + k] = float(c[2 - k]) / 255.0f;
  }
  turbo.upload(256, 1, 3, rgb.data());
}

}  // namespace goris::ui
