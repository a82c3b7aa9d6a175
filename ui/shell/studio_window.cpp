#include "ui/shell/studio_window.h"

#include "ui/gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "core/util/error.h"

namespace goris::ui {

namespace {
std::string g_glfw_error;
void on_glfw_error(int code, const char* text) {
  g_glfw_error = std::string(text) + " (GLFW error " + std::to_string(code) + ")";
}
}  // namespace

StudioWindow::StudioWindow(int width, int height, const std::string& title) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit())
    throw Error("display", "cannot start GLFW: " + (g_glfw_error.empty() ? std::string("no display?") : g_glfw_error));
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string why = g_glfw_error;
    glfwTerminate();
    throw Error("display", "cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
                               " window with OpenGL 3.3 core: " + why);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);  // the frame limiter paces frames; vsync would stall the loop on some drivers

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is computed, and settings live in settings.json
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 0.0f;
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

StudioWindow::~StudioWindow() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool StudioWindow::should_close() const { return glfwWindowShouldClose(window_); }
void StudioWindow::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void StudioWindow::process_events(double timeout_s) {
  if (timeout_s > 0)
    glfwWaitEventsTimeout(timeout_s);
  else
    glfwPollEvents();
}

void StudioWindow::begin_frame(const std::optional<ScriptedMouse>& mouse) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  if (mouse) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(mouse->pos.x, mouse->pos.y);
    io.MouseDown[ImGuiMouseButton_Left] = mouse->left_down;
    io.KeyShift = mouse->shift;
    io.KeyCtrl = mouse->ctrl;
    io.KeyAlt = mouse->alt;
  }
  ImGui::NewFrame();
}

void StudioWindow::render() {
  ImGui::Render();
  const glm::ivec2 fb = framebuffer_size();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb.x, fb.y);
  glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void StudioWindow::present() { glfwSwapBuffers(window_); }

glm::ivec2 StudioWindow::window_size() const {
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  return {w, h};
}

glm::ivec2 StudioWindow::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

std::string StudioWindow::gl_description() const {
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + ", OpenGL " + (version ? version : "?");
}

}  // namespace goris::ui
