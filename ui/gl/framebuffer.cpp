#include "ui/gl/framebuffer.h"

#include "core/util/error.h"

namespace goris::ui {

Framebuffer::~Framebuffer() { release(); }

void Framebuffer::release() {
  if (texture_) glDeleteTextures(1, &texture_);
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  texture_ = fbo_ = 0;
  width_ = height_ = 0;
}

bool Framebuffer::resize(int width, int height) {
  width = width < 1 ? 1 : width;
  height = height < 1 ? 1 : height;
  if (fbo_ && width == width_ && height == height_) return false;
  release();
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    release();
    throw Error("OpenGL", "viewport framebuffer " + std::to_string(width) + "x" + std::to_string(height) +
                              " is incomplete (status " + std::to_string(status) + ")");
  }
  width_ = width;
  height_ = height;
  return true;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

}  // namespace goris::ui
