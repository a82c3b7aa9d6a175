#pragma once
// Draws one channel of the current frame into a viewport's framebuffer with the GLSL colour maps of
// shaders/ (colormaps.glsl + channel.frag.glsl), with the selection tint and the label overlay.
#include <filesystem>

#include "render/maps/channels.h"
#include "ui/display/frame_textures.h"
#include "ui/gl/framebuffer.h"
#include "ui/gl/shader_program.h"

namespace goris::ui {

struct ChannelDrawOptions {
  Channel channel = Channel::Final;
  bool label_overlay = false;  // tint pixels whose object label exceeds 0.5
  bool selection = true;       // tint the selection's coverage (when the frame has one)
  bool photo = false;          // show the input photo right of `split`
  float split = 0.5f;
};

class ChannelRenderer {
 public:
  // Loads and links the shaders from `shader_dir`; throws goris::Error naming a file that fails.
  explicit ChannelRenderer(const std::filesystem::path& shader_dir);
  ~ChannelRenderer();
  ChannelRenderer(const ChannelRenderer&) = delete;
  ChannelRenderer& operator=(const ChannelRenderer&) = delete;

  void draw(const Framebuffer& target, const FrameTextures& textures, const ChannelDrawOptions& options);

 private:
  ShaderProgram program_;
  GLuint vao_ = 0;
};

}  // namespace goris::ui
