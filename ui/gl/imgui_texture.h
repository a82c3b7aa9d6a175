#pragma once
// A GL texture as ImGui::Image takes it (the OpenGL3 backend's ImTextureID is the texture name).
#include <imgui.h>

#include <cstdint>

#include "ui/gl/gl_api.h"

namespace goris::ui {

inline ImTextureID imgui_texture(GLuint texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture));
}

}  // namespace goris::ui
