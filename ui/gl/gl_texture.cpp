#include "ui/gl/gl_texture.h"

#include <utility>

#include "core/util/error.h"

namespace goris::ui {

GlTexture::~GlTexture() {
  if (id_) glDeleteTextures(1, &id_);
}

GlTexture::GlTexture(GlTexture&& o) noexcept
    : id_(std::exchange(o.id_, 0)), width_(o.width_), height_(o.height_), channels_(o.channels_) {}

GlTexture& GlTexture::operator=(GlTexture&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteTextures(1, &id_);
    id_ = std::exchange(o.id_, 0);
    width_ = o.width_;
    height_ = o.height_;
    channels_ = o.channels_;
  }
  return *this;
}

namespace {
constexpr GLenum kInternal[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
constexpr GLenum kFormat[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
}  // namespace

bool GlTexture::prepare(int width, int height, int channels, const float* data) {
  if (channels < 1 || channels > 4 || width <= 0 || height <= 0)
    throw Error("texture upload: bad size " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                std::to_string(channels));
  if (!id_) {
    glGenTextures(1, &id_);
    glBindTexture(GL_TEXTURE_2D, id_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (width == width_ && height == height_ && channels == channels_) return false;
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(kInternal[channels - 1]), width, height, 0, kFormat[channels - 1], GL_FLOAT,
               data);
  width_ = width;
  height_ = height;
  channels_ = channels;
  return true;
}

void GlTexture::upload(int width, int height, int channels, const float* data) {
  if (!prepare(width, height, channels, data))
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, kFormat[channels - 1], GL_FLOAT, data);
  check_gl("texture upload");
}

bool GlTexture::allocate(int width, int height, int channels) {
  const bool changed = prepare(width, height, channels, nullptr);
  check_gl("texture allocation");
  return changed;
}

void GlTexture::bind(int unit) const {
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  glBindTexture(GL_TEXTURE_2D, id_);
}

}  // namespace goris::ui
