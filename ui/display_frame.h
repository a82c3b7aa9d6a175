#pragma once
// One rendered view for the viewports: the G-buffer channels on the host, interleaved row by row (top row
// first) the way they are uploaded as textures, plus what the colour maps need (the depth range); for
// intrinsic runs the intrinsic renderer's maps, and the selection's coverage when something is selected.
// Also answers "what is under this pixel" (depth, opacity, world position) for clicks.
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/io/camera.h"
#include "render/intrinsic/intrinsic_renderer.h"
#include "render/raster/rasterizer.h"

namespace goris::ui {

struct DisplayFrame {
  std::uint64_t id = 0;  // the request it answers
  Camera camera;         // at the frame's size
  int width = 0, height = 0;
  std::vector<float> color;    // [H][W][3]
  std::vector<float> normal;   // [H][W][3] unit camera-space normal, 0 where nothing was hit
  std::vector<float> diffuse;  // [H][W][3]
  std::vector<float> fresnel;  // [H][W][3]
  std::vector<float> misc;     // [H][W][4] roughness, region, label, alpha
  std::vector<float> depth;    // [H][W] expected depth (camera z), 0 where alpha is below kMinAlpha
  // Intrinsic runs (empty otherwise): `color` is then the shaded C.
  std::vector<float> glossy;    // [H][W][3] G
  std::vector<float> indirect;  // [H][W][3] L_ind'
  std::vector<float> env;       // [H][W][3] L_dir'
  std::vector<float> light;     // [H][W][2] V', R_s (0 without the screen-space filter)
  bool screen_roughness = false;
  // L_ind' is shown with automatic exposure: indirect light is usually far dimmer than the rest, so its
  // 99th percentile (over the pixels that have any) is mapped to white; never darker than as is.
  float indirect_gain = 1.0f;
  static constexpr float kMaxIndirectGain = 64.0f;
  // Coverage of the selected Gaussians ([H][W], alpha-blended 0/1 per Gaussian); empty = no selection.
  std::vector<float> selection;
  // Inverse depth at the 99th / 1st percentile of covered pixels: the TURBO map's near (red) and far
  // (blue) ends, as `goris render --maps` maps them.
  float inv_depth_near = 1, inv_depth_far = 0;
  int model_iteration = 0;
  size_t gaussians = 0;
  double render_ms = 0;

  static constexpr float kMinAlpha = 0.05f;
  size_t pixels() const { return size_t(width) * size_t(height); }
  bool intrinsic() const { return !glossy.empty(); }
};

// The host frame of a G-buffer rendered with `camera` (any device; extras optional: zero without them).
DisplayFrame make_display_frame(const GBuffer& gbuffer, const Camera& camera);
// Adds an intrinsic render's maps (same size; planar as IntrinsicMaps holds them): the shaded colour
// replaces `color`. Throws goris::Error when the sizes differ.
void add_intrinsic_maps(DisplayFrame& frame, const IntrinsicMaps& maps);
// Adds the selection's coverage from a one-channel G-buffer extra ([1][H][W], same size).
void add_selection_coverage(DisplayFrame& frame, const std::vector<float>& coverage);

struct PickResult {
  int x = 0, y = 0;       // frame pixel
  float alpha = 0;        // accumulated opacity there
  float depth = 0;        // expected camera z (0 when nothing is there)
  glm::vec3 world{0.0f};  // the surface point (valid when hit)
  bool hit = false;       // alpha >= kMinAlpha
};

// What lies under continuous frame pixel coordinates (u, v) (pixel centres at +0.5); nullopt outside.
std::optional<PickResult> pick(const DisplayFrame& frame, float u, float v);

}  // namespace goris::ui
