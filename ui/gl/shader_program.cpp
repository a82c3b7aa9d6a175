#include "ui/gl/shader_program.h"

#include <fstream>
#include <sstream>
#include <utility>

#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), fs::exists(path) ? "cannot be read" : "shader file not found");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string join_names(const std::vector<fs::path>& files) {
  std::string s;
  for (const fs::path& f : files) s += (s.empty() ? "" : " + ") + f.string();
  return s;
}

GLuint compile(GLenum stage, const std::string& source, const std::string& name) {
  const GLuint s = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(len > 0 ? len : 1), '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    // Line numbers in the log count from the added #version line (1) onwards.
    throw Error(name, "does not compile (log line numbers count the added #version line):\n" + log);
  }
  return s;
}

}  // namespace

ShaderProgram::~ShaderProgram() {
  if (id_) glDeleteProgram(id_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& o) noexcept
    : id_(std::exchange(o.id_, 0)), locations_(std::move(o.locations_)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
    locations_ = std::move(o.locations_);
  }
  return *this;
}

ShaderProgram ShaderProgram::from_files(const std::vector<fs::path>& vertex, const std::vector<fs::path>& fragment) {
  std::string vs = "#version 330 core\n", fs_src = "#version 330 core\n";
  for (const fs::path& f : vertex) vs += read_text(f) + "\n";
  for (const fs::path& f : fragment) fs_src += read_text(f) + "\n";
  ShaderProgram p;
  const GLuint v = compile(GL_VERTEX_SHADER, vs, join_names(vertex));
  GLuint f = 0;
  try {
    f = compile(GL_FRAGMENT_SHADER, fs_src, join_names(fragment));
  } catch (...) {
    glDeleteShader(v);
    throw;
  }
  p.id_ = glCreateProgram();
  glAttachShader(p.id_, v);
  glAttachShader(p.id_, f);
  glLinkProgram(p.id_);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p.id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(p.id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(len > 0 ? len : 1), '\0');
    glGetProgramInfoLog(p.id_, len, nullptr, log.data());
    throw Error(join_names(vertex) + ", " + join_names(fragment), "do not link:\n" + log);
  }
  return p;
}

GLint ShaderProgram::location(const char* name) {
  const auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id_, name);
  locations_.emplace(name, loc);
  return loc;
}

void ShaderProgram::set(const char* name, int v) { glUniform1i(location(name), v); }
void ShaderProgram::set(const char* name, float v) { glUniform1f(location(name), v); }
void ShaderProgram::set(const char* name, const glm::vec2& v) { glUniform2f(location(name), v.x, v.y); }
void ShaderProgram::set(const char* name, const glm::vec3& v) { glUniform3f(location(name), v.x, v.y, v.z); }

}  // namespace goris::ui
