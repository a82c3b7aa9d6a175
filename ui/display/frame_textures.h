#pragma once
// The GPU side of the current DisplayFrame: one texture per group of channels, shared by every viewport
// (they all show the same view in different channels), plus the comparison photo, the removal masks of the
// snapped training view and the TURBO lookup table.
//
// How images reach the textures: host images (CPU frames, the intrinsic maps, depth) by a texture upload;
// a CUDA frame's device images by a device-to-device copy through CUDA-GL interop. When interop fails (e.g.
// a Mesa GL context beside a CUDA device) the device images are brought to the host and uploaded instead,
// from then on, after one message on stderr.
#include <cstdint>
#include <string>

#include "core/io/image.h"
#include "render/maps/channels.h"
#include "ui/display/display_frame.h"
#include "ui/gl/cuda_texture_interop.h"
#include "ui/gl/gl_texture.h"

namespace goris::ui {

// How one image of a frame reaches its texture.
enum class UploadPath {
  Host,          // from host memory (CPU images)
  Interop,       // CUDA image, device to device through CUDA-GL interop
  DeviceToHost,  // CUDA image brought to the host first: interop not compiled in, or it failed once
};
UploadPath upload_path(Device image_device, bool interop_compiled, bool interop_failed);

struct FrameTextures {
  GlTexture color, normal, diffuse, fresnel, misc, depth;  // see DisplayFrame for the layouts
  GlTexture glossy, indirect, env, light;  // intrinsic frames only (has_intrinsic)
  GlTexture traced;                        // with the screen-space filter only (has_screen_roughness)
  GlTexture selection;                     // coverage of the selection (has_selection)
  GlTexture photo;  // the input photo of the nearest training camera (RGB, top row first)
  GlTexture lighting_mask, inpaint_mask;  // RUN/removal/*_masks/VIEW.png of `masks_view` (one channel)
  GlTexture turbo;  // 256 x 1 TURBO colours
  int width = 0, height = 0;
  float inv_depth_near = 1, inv_depth_far = 0;
  float indirect_gain = 1;  // DisplayFrame::indirect_gain
  bool has_intrinsic = false, has_screen_roughness = false, has_selection = false;
  bool has_lighting_mask = false, has_inpaint_mask = false;
  std::string masks_key;       // what the mask textures were loaded for (folder + view), empty = none
  std::uint64_t frame_id = 0;  // the DisplayFrame shown
  std::uint64_t version = 0;   // grows with every upload (viewports redraw when it changes)
  bool has_frame() const { return width > 0; }
  // Whether the textures hold `c` for the current frame.
  bool has(Channel c) const;

  void upload(const DisplayFrame& frame);
  void upload_photo(const Image& rgb);  // an RGB image on any device
  // The removal masks for `key`; a null image leaves that mask absent.
  void upload_masks(const std::string& key, const Image* lighting, const Image* inpaint);
  void create_turbo_table();  // once, after the GL context exists

  // Why CUDA-GL interop was given up (empty while it works or was never needed).
  const std::string& interop_failure() const { return interop_failure_; }

 private:
  // One image of the frame: from `device` when it holds it (interleaved, frame_layout.h), else from `host`.
  void put(GlTexture& texture, int width, int height, int host_channels, const std::vector<float>& host,
           const Buffer<float>& device);
  // Drops the interop registration of a texture whose storage is about to change.
  void before_respecify(const GlTexture& texture, int width, int height, int channels);

  bool interop_failed_ = false;
  std::string interop_failure_;
  CudaTextureInterop interop_;  // declared after the textures: unregisters them before they are deleted
};

}  // namespace goris::ui
