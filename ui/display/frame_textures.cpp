#include "ui/display/frame_textures.h"

#include <iostream>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "ui/display/frame_layout.h"

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

UploadPath upload_path(Device image_device, bool interop_compiled, bool interop_failed) {
  if (image_device == Device::CPU) return UploadPath::Host;
  return interop_compiled && !interop_failed ? UploadPath::Interop : UploadPath::DeviceToHost;
}

void FrameTextures::before_respecify(const GlTexture& t, int width, int height, int channels) {
  if (!t.empty() && (t.width() != width || t.height() != height || t.channels() != channels)) interop_.forget(t.id());
}

void FrameTextures::put(GlTexture& t, int w, int h, int host_channels, const std::vector<float>& host,
                        const Buffer<float>& device) {
  if (device.empty()) {
    before_respecify(t, w, h, host_channels);
    t.upload(w, h, host_channels, host.data());
    return;
  }
  const int c = frame_layout::interop_channels(host_channels);
  before_respecify(t, w, h, c);
  switch (upload_path(device.device(), cuda_compiled(), interop_failed_)) {
    case UploadPath::Host:
      t.upload(w, h, c, device.data());
      return;
    case UploadPath::Interop:
      try {
        t.allocate(w, h, c);
        interop_.copy(t.id(), w, h, c, device.data());
        return;
      } catch (const std::exception& e) {
        interop_failed_ = true;
        interop_failure_ = e.what();
        std::cerr << "goris-studio: CUDA-GL interop unavailable (" << interop_failure_
                  << "); viewport images now go through host memory\n";
      }
      [[fallthrough]];
    case UploadPath::DeviceToHost: {
      const std::vector<float> px = device.to_host();
      t.upload(w, h, c, px.data());
      return;
    }
  }
}

void FrameTextures::upload(const DisplayFrame& f) {
  put(color, f.width, f.height, 3, f.color, f.gpu.color);
  put(normal, f.width, f.height, 3, f.normal, f.gpu.normal);
  put(diffuse, f.width, f.height, 3, f.diffuse, f.gpu.diffuse);
  put(fresnel, f.width, f.height, 3, f.fresnel, f.gpu.fresnel);
  put(misc, f.width, f.height, 4, f.misc, f.gpu.misc);
  depth.upload(f.width, f.height, 1, f.depth.data());  // host always (picking reads it there)
  has_intrinsic = f.intrinsic();
  has_screen_roughness = has_intrinsic && f.screen_roughness;
  if (has_intrinsic) {
    glossy.upload(f.width, f.height, 3, f.glossy.data());
    indirect.upload(f.width, f.height, 3, f.indirect.data());
    env.upload(f.width, f.height, 3, f.env.data());
    light.upload(f.width, f.height, 2, f.light.data());
  }
  if (has_screen_roughness) traced.upload(f.width, f.height, 4, f.traced.data());
  has_selection = f.has_selection();
  if (has_selection) put(selection, f.width, f.height, 1, f.selection, f.gpu.selection);
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
