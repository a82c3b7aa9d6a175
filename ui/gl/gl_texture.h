#pragma once
// An owned 2D texture of float data (1-4 channels), rows stored as given (top row first for images; the
// display shader flips). Linear filtering, clamped edges.
#include "ui/gl/gl_api.h"

namespace goris::ui {

class GlTexture {
 public:
  GlTexture() = default;
  ~GlTexture();
  GlTexture(GlTexture&& o) noexcept;
  GlTexture& operator=(GlTexture&& o) noexcept;
  GlTexture(const GlTexture&) = delete;
  GlTexture& operator=(const GlTexture&) = delete;

  // Uploads width x height pixels of `channels` interleaved floats (reallocating when the size changes).
  void upload(int width, int height, int channels, const float* data);
  // Makes the storage width x height x `channels` floats (contents undefined) unless it already is; true
  // when it was (re)specified, which invalidates a CUDA registration of the texture. For copies that do not
  // come from host memory (CUDA-GL interop).
  bool allocate(int width, int height, int channels);
  void bind(int unit) const;
  GLuint id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  bool empty() const { return id_ == 0; }

 private:
  // Creates the texture when needed and binds it; (re)specifies the storage with `data` (may be null) when
  // the size or format differs. Returns whether it did.
  bool prepare(int width, int height, int channels, const float* data);

  GLuint id_ = 0;
  int width_ = 0, height_ = 0, channels_ = 0;
};

}  // namespace goris::ui
