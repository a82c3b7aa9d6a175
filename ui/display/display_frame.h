#pragma once
// One rendered view for the viewports: the G-buffer channels interleaved row by row (top row first) the way
// they are uploaded as textures, plus what the colour maps need (the depth range); for intrinsic runs the
// intrinsic renderer's maps, and the selection's coverage when something is selected. Also answers "what
// is under this pixel" (depth, opacity, world position) for clicks.
//
// Where the images live follows the G-buffer: a CPU render fills the host vectors; a CUDA render keeps its
// images on the GPU (`gpu`, copied into GL through CUDA-GL interop by FrameTextures) and brings to the host
// only what the GUI reads there (depth and alpha for picking, the depth range).
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "core/compute/buffer.h"
#include "core/io/camera.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "render/raster/rasterizer.h"

namespace goris::ui {

// The images of a CUDA frame, interleaved [H][W][C] on the G-buffer's device (frame_layout.h): 3-channel maps
// padded to 4 (alpha 1). An empty buffer means the image is on the host (or absent), as in a CPU frame.
struct DeviceImages {
  Buffer<float> color, normal, diffuse, fresnel;  // [H][W][4]
  Buffer<float> misc;                             // [H][W][4] roughness, region, label, alpha
  Buffer<float> selection;                        // [H][W] coverage clamped to [0, 1]; empty = no selection
  bool any() const { return !color.empty() || !normal.empty() || !misc.empty() || !selection.empty(); }
};

struct DisplayFrame {
  std::uint64_t id = 0;  // the request it answers
  Camera camera;         // at the frame's size
  int width = 0, height = 0;
  // On the host for CPU frames; for CUDA frames color/normal/diffuse/fresnel/misc/selection are empty here
  // and live in `gpu` (except `color` of intrinsic frames, which the intrinsic maps bring on the host).
  std::vector<float> color;    // [H][W][3]
  std::vector<float> normal;   // [H][W][3] unit camera-space normal, 0 where nothing was hit
  std::vector<float> diffuse;  // [H][W][3]
  std::vector<float> fresnel;  // [H][W][3]
  std::vector<float> misc;     // [H][W][4] roughness, region, label, alpha
  std::vector<float> depth;    // [H][W] expected depth (camera z), 0 where alpha is below kMinAlpha (host always)
  std::vector<float> alpha;    // [H][W] accumulated opacity (host always: picking reads it)
  // Intrinsic runs (empty otherwise): `color` is then the shaded C.
  std::vector<float> glossy;    // [H][W][3] G
  std::vector<float> indirect;  // [H][W][3] L_ind'
  std::vector<float> env;       // [H][W][3] L_dir'
  std::vector<float> light;     // [H][W][2] V', R_s (0 without the screen-space filter)
  bool screen_roughness = false;
  // [H][W][4] L_ind rgb and V as traced, before the screen-space filter (filled exactly when
  // screen_roughness is true; empty otherwise).
  std::vector<float> traced;
  // L_ind' is shown with automatic exposure: indirect light is usually far dimmer than the rest, so its
  // 99th percentile (over the pixels that have any) is mapped to white; never darker than as is.
  float indirect_gain = 1.0f;
  static constexpr float kMaxIndirectGain = 64.0f;
  // Coverage of the selected Gaussians ([H][W], alpha-blended 0/1 per Gaussian); empty = no selection.
  std::vector<float> selection;
  DeviceImages gpu;  // CUDA frames (see above)
  // Inverse depth at the 99th / 1st percentile of covered pixels: the TURBO map's near (red) and far
  // (blue) ends, as `goris render --maps` maps them.
  float inv_depth_near = 1, inv_depth_far = 0;
  int model_iteration = 0;
  size_t gaussians = 0;
  double render_ms = 0;

  static constexpr float kMinAlpha = 0.05f;
  size_t pixels() const { return size_t(width) * size_t(height); }
  bool intrinsic() const { return !glossy.empty(); }
  bool has_selection() const { return !selection.empty() || !gpu.selection.empty(); }
};

// The frame of a G-buffer rendered with `camera` (extras optional: zero without them): host images for a
// CPU G-buffer, device images (make_device_display_frame) for a CUDA one.
DisplayFrame make_display_frame(const GBuffer& gbuffer, const Camera& camera);
// The CUDA frame layout on the G-buffer's own device, whichever it is (the tests build it on the CPU):
// images in `gpu`, depth, alpha and the depth range on the host.
DisplayFrame make_device_display_frame(const GBuffer& gbuffer, const Camera& camera);
// Adds an intrinsic render's maps (same size; planar as IntrinsicMaps holds them): the shaded colour
// replaces `color`. Throws goris::Error when the sizes differ.
void add_intrinsic_maps(DisplayFrame& frame, const IntrinsicMaps& maps);
// Adds the selection's coverage from a one-channel G-buffer extra ([1][H][W], same size).
void add_selection_coverage(DisplayFrame& frame, const std::vector<float>& coverage);
// The same from a buffer on any device: kept on the device for a frame whose images are there (`gpu`),
// else brought to the host.
void add_selection_coverage(DisplayFrame& frame, const Buffer<float>& coverage);

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
