#pragma once
// One viewport: an ImGui window at a given rectangle showing one channel of the current frame (drawn
// into its own framebuffer by the channel shader), with its channel chooser, and the mouse controls of
// the view camera (left drag orbit / look, right or middle drag pan, wheel zoom, left click = pick); the main
// viewport also runs the selection tools (ui/viewport/viewport_tools.h) on its left button.
#include <string>

#include "ui/document/app_state.h"
#include "ui/display/channel_renderer.h"
#include "ui/display/frame_textures.h"
#include "ui/gl/framebuffer.h"
#include "ui/document/panel_layout.h"
#include "ui/viewport/viewport_tools.h"

namespace goris::ui {

enum class CameraMode { Orbit, Fly };

struct ViewportContext {
  AppState& state;
  FrameTextures& textures;
  ChannelRenderer& renderer;
  CameraMode mode = CameraMode::Orbit;
  float framebuffer_scale = 1.0f;  // framebuffer pixels per window pixel
  const char* empty_text = "";     // shown when there is no frame
};

class Viewport {
 public:
  // index -1 = the main viewport, 0.. = grid tiles.
  explicit Viewport(int index);

  // Draws at `rect` (window pixels). `photo_half`: side by side, the right half shows the input photo.
  void draw(const Rect& rect, ViewportContext& ctx, bool photo_half = false);

  int index() const { return index_; }
  std::string name() const;
  // Where the rendered image was drawn last frame (window pixels; w = 0 when none).
  const Rect& image_rect() const { return image_; }
  bool hovered() const { return hovered_; }

 private:
  void draw_image(ViewportContext& ctx, const Rect& r, Channel c);
  void handle_mouse(ViewportContext& ctx);
  void draw_chooser(ViewportContext& ctx, Channel current);

  int index_;
  Framebuffer fbo_;
  std::uint64_t drawn_version_ = 0;
  ChannelDrawOptions drawn_;
  bool has_drawn_ = false;
  Rect image_;
  bool hovered_ = false;
  bool dragged_ = false;
  ViewportTools tools_;  // the main viewport's
};

}  // namespace goris::ui
