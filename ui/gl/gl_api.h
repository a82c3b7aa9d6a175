#pragma once
// OpenGL 3.3 core declarations for the editor. GLVND's libOpenGL exports every core entry point, so the
// prototypes of glcorearb.h link directly and no loader library is needed. Include this instead of any
// other GL header (GLFW is included with GLFW_INCLUDE_NONE).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace goris::ui {

// Throws goris::Error("OpenGL", "<what>: <error name>") when glGetError reports a problem.
void check_gl(const std::string& what);

}  // namespace goris::ui
