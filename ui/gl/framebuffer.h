#pragma once
// An owned off-screen RGBA8 colour target: a viewport draws its channel into one, then ImGui shows the
// texture. GL convention: row 0 is the bottom (show it with uv0 = (0, 1), uv1 = (1, 0)).
#include "ui/gl/gl_api.h"

namespace goris::ui {

class Framebuffer {
 public:
  Framebuffer() = default;
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // (Re)allocates for width x height; returns true when the size changed (the contents are then undefined).
  bool resize(int width, int height);
  // Binds it as the draw target with a matching viewport.
  void bind() const;
  GLuint texture() const { return texture_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void release();
  GLuint fbo_ = 0, texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace goris::ui
