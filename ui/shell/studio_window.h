#pragma once
// The editor's window: GLFW with an OpenGL 3.3 core context and Dear ImGui (Debian's libimgui with its
// GLFW and OpenGL3 backends). Owns nothing of the document.
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "ui/script/scripted_mouse.h"

struct GLFWwindow;

namespace goris::ui {

class StudioWindow {
 public:
  // Throws goris::Error("display", ...) when GLFW cannot start (no display) or the context cannot be made.
  StudioWindow(int width, int height, const std::string& title);
  ~StudioWindow();
  StudioWindow(const StudioWindow&) = delete;
  StudioWindow& operator=(const StudioWindow&) = delete;

  bool should_close() const;
  void request_close();
  // Waits up to timeout_s for input (idle) or just takes what arrived (timeout_s <= 0).
  void process_events(double timeout_s);
  void begin_frame(const std::optional<ScriptedMouse>& mouse = std::nullopt);  // starts an ImGui frame
  void render();       // ImGui draw data into the default framebuffer (not yet shown)
  void present();      // swap buffers

  glm::ivec2 window_size() const;
  glm::ivec2 framebuffer_size() const;
  GLFWwindow* handle() const { return window_; }
  std::string gl_description() const;  // renderer and version, for the debug overlay

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace goris::ui
