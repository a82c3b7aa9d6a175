#pragma once
// The GPU side of the current DisplayFrame: one texture per group of channels, shared by every viewport
// (they all show the same view in different channels), plus the comparison photo, the removal masks of the
// snapped training view and the TURBO lookup table.
#include <cstdint>
#include <string>

#include "core/io/image.h"
#include "ui/channels.h"
#include "ui/display_frame.h"
#include "ui/gl/gl_texture.h"

namespace goris::ui {

struct FrameTextures {
  GlTexture color, normal, diffuse, fresnel, misc, depth;  // see DisplayFrame for the layouts
  GlTexture glossy, indirect, env, light;  // intrinsic frames only (has_intrinsic)
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
};

}  // namespace goris::ui
