#include "ui/display/channel_renderer.h"

#include "core/util/error.h"

namespace goris::ui {

namespace {

struct Source {
  const GlTexture* texture;
  int map;        // as u_map in channel.frag.glsl
  int component;  // for the grey map
};

Source source_of(Channel c, const FrameTextures& t) {
  switch (channel_info(c).map) {
    case ColorMap::TurboInverseDepth:
      return {&t.depth, 2, 0};
    case ColorMap::NormalRgb:
      return {&t.normal, 3, 0};
    default:
      break;
  }
  switch (c) {
    case Channel::Final:
      return {&t.color, 0, 0};
    case Channel::Diffuse:
      return {&t.diffuse, 0, 0};
    case Channel::Fresnel:
      return {&t.fresnel, 0, 0};
    case Channel::Roughness:
      return {&t.misc, 1, 0};
    case Channel::Region:
      return {&t.misc, 1, 1};
    case Channel::Label:
      return {&t.misc, 1, 2};
    case Channel::Alpha:
      return {&t.misc, 1, 3};
    case Channel::Glossy:
      return {&t.glossy, 0, 0};
    case Channel::IndirectLight:
      return {&t.indirect, 0, 0};
    case Channel::EnvLight:
      return {&t.env, 0, 0};
    case Channel::Visibility:
      return {&t.light, 1, 0};
    case Channel::ScreenRoughness:
      return {&t.light, 1, 1};
    case Channel::TracedIndirect:
      return {&t.traced, 0, 0};
    case Channel::TracedVisibility:
      return {&t.traced, 1, 3};
    case Channel::LightingMask:
      return {&t.lighting_mask, 1, 0};
    case Channel::InpaintMask:
      return {&t.inpaint_mask, 1, 0};
    default:
      break;
  }
  throw Error(std::string("channel '") + channel_info(c).id + "': no colour map");
}

}  // namespace

ChannelRenderer::ChannelRenderer(const std::filesystem::path& dir)
    : program_(ShaderProgram::from_files({dir / "viewport.vert.glsl"},
                                         {dir / "colormaps.glsl", dir / "channel.frag.glsl"})) {
  glGenVertexArrays(1, &vao_);  // core profile: a bound VAO is required even without attributes
}

ChannelRenderer::~ChannelRenderer() {
  if (vao_) glDeleteVertexArrays(1, &vao_);
}

void ChannelRenderer::draw(const Framebuffer& target, const FrameTextures& t, const ChannelDrawOptions& o) {
  if (!t.has(o.channel))
    throw Error(std::string("channel '") + channel_info(o.channel).id + "': not in the current frame");
  const Source src = source_of(o.channel, t);
  target.bind();
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  program_.use();
  src.texture->bind(0);
  t.misc.bind(1);
  t.turbo.bind(2);
  const bool photo = o.photo && !t.photo.empty();
  if (photo) t.photo.bind(3);
  const bool selection = o.selection && t.has_selection;
  if (selection) t.selection.bind(4);
  program_.set("u_source", 0);
  program_.set("u_overlay", 1);
  program_.set("u_turbo", 2);
  program_.set("u_photo", 3);
  program_.set("u_selection", 4);
  program_.set("u_selection_on", selection ? 1 : 0);
  program_.set("u_selection_tint", glm::vec3(1.0f, 0.1f, 0.7f));
  program_.set("u_map", src.map);
  program_.set("u_component", src.component);
  // Both L_ind channels share one exposure, so the traced and the filtered light compare as they are.
  const bool indirect = o.channel == Channel::IndirectLight || o.channel == Channel::TracedIndirect;
  program_.set("u_gain", indirect ? t.indirect_gain : 1.0f);
  program_.set("u_inv_near", t.inv_depth_near);
  program_.set("u_inv_far", t.inv_depth_far);
  program_.set("u_overlay_on", o.label_overlay ? 1 : 0);
  program_.set("u_overlay_component", 2);  // label in the misc texture
  program_.set("u_overlay_threshold", 0.5f);
  program_.set("u_tint", glm::vec3(1.0f, 0.85f, 0.1f));  // label: yellow, unlike the selection's magenta
  program_.set("u_photo_on", photo ? 1 : 0);
  program_.set("u_split", o.split);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("drawing viewport channel");
}

}  // namespace goris::ui
