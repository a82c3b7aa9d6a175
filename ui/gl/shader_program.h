#pragma once
// A GLSL program built from source files. Each stage may be several files concatenated in order (shared
// functions first), after a `#version 330 core` line this class adds, so the files hold no #version.
// Compile and link errors throw goris::Error naming the file(s) with the driver's log.
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "ui/gl/gl_api.h"

namespace goris::ui {

class ShaderProgram {
 public:
  ShaderProgram() = default;
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& o) noexcept;
  ShaderProgram& operator=(ShaderProgram&& o) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  static ShaderProgram from_files(const std::vector<std::filesystem::path>& vertex,
                                  const std::vector<std::filesystem::path>& fragment);

  void use() const { glUseProgram(id_); }
  GLuint id() const { return id_; }
  // Uniform setters (the program must be in use); unknown names are ignored like GL does (location -1).
  void set(const char* name, int v);
  void set(const char* name, float v);
  void set(const char* name, const glm::vec2& v);
  void set(const char* name, const glm::vec3& v);

 private:
  GLint location(const char* name);
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace goris::ui
