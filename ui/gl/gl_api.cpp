#include "ui/gl/gl_api.h"

#include "core/util/error.h"

namespace goris::ui {

void check_gl(const std::string& what) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return;
  const char* name = "unknown error";
  switch (e) {
    case GL_INVALID_ENUM:
      name = "GL_INVALID_ENUM";
      break;
    case GL_INVALID_VALUE:
      name = "GL_INVALID_VALUE";
      break;
    case GL_INVALID_OPERATION:
      name = "GL_INVALID_OPERATION";
      break;
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      name = "GL_INVALID_FRAMEBUFFER_OPERATION";
      break;
    case GL_OUT_OF_MEMORY:
      name = "GL_OUT_OF_MEMORY";
      break;
  }
  while (glGetError() != GL_NO_ERROR) {
  }
  throw Error("OpenGL", what + ": " + name);
}

}  // namespace goris::ui
