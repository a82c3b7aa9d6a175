#pragma once
// Data types of the G-buffer rasterizer, templated on the scalar type: float in production, double in the
// finite-difference gradient tests. Public float aliases and entry points are in rasterizer.h.
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "core/compute/buffer.h"
#include "core/io/camera.h"

namespace goris {

constexpr int kTileSize = 16;  // 16x16 pixel tiles, as in 3DGS

struct RasterSettings {
  glm::vec3 background{0.0f};        // blended into `color` with the final transmittance
  float filter2d_var = 0.3f;         // added to the diagonal of every projected 2D covariance (pixels^2)
  bool filter2d_compensate = false;  // Mip-Splatting 2D filter: opacity *= sqrt(det(S2) / det(S2 + filter))
  float near_plane = 0.2f;           // Gaussians with camera-space z <= near_plane are culled
  bool profile = false;              // record per-stage times in RasterStateT::times (synchronises CUDA)

  // Plain 3DGS rule (the fixture's): dilation 0.3, no opacity compensation.
  static RasterSettings classic_3dgs() { return RasterSettings{}; }
  // Mip-Splatting's 2D filter: dilation 0.1 with opacity compensation.
  static RasterSettings mip_splatting() {
    RasterSettings s;
    s.filter2d_var = 0.1f;
    s.filter2d_compensate = true;
    return s;
  }
};

// Per-Gaussian parameters as the rasterizer reads them; same layouts and meaning as GaussianView
// (core/scene/gaussian_view.h), with the scalar type as a parameter.
template <class T>
struct GaussiansT {
  int count = 0;
  const T* positions = nullptr;       // [N][3]
  const T* log_scales = nullptr;      // [N][3]
  const T* rotations = nullptr;       // [N][4] (w, x, y, z), not necessarily normalised
  const T* opacity_logits = nullptr;  // [N]
  const T* sh = nullptr;              // [N][16][3], coefficient-major
  int sh_degree = 0;                  // 0..3
  const T* extras = nullptr;          // [N][n_extras], already activated
  int n_extras = 0;
  const T* filter3d_var = nullptr;    // [N] Mip-Splatting 3D filter variance, or null
};

// Where gradients are accumulated (+=); null pointers are skipped.
template <class T>
struct GaussianGradsT {
  T* positions = nullptr;
  T* log_scales = nullptr;
  T* rotations = nullptr;
  T* opacity_logits = nullptr;
  T* sh = nullptr;  // only the first (sh_degree+1)^2 coefficients of each Gaussian are written
  T* extras = nullptr;
  T* mean2d_grad_norm = nullptr;  // += |dL/dmean2d| in pixels, for every Gaussian with radius > 0
};

// The G-buffer: planar images, row-major [H][W] per channel.
template <class T>
struct GBufferT {
  int width = 0, height = 0, n_extras = 0;
  Buffer<T> color;         // [3][H][W]  sum_i w_i c_i + T_final * background   (w_i = alpha_i * T_i)
  Buffer<T> alpha;         // [H][W]     1 - T_final
  Buffer<T> depth;         // [H][W]     sum_i w_i z_i (camera z on each Gaussian's depth plane; NOT divided by alpha)
  Buffer<T> median_depth;  // [H][W]     z of the Gaussian at which T drops to 0.5 or below (last one if never); 0 if none
  Buffer<T> normal;        // [3][H][W]  sum_i w_i n_i, camera space, unit n_i facing the camera; NOT normalised
  Buffer<T> extras;        // [K][H][W]  sum_i w_i e_i
  std::size_t pixels() const { return std::size_t(width) * std::size_t(height); }
};

// dL/d(G-buffer), same layouts as GBufferT, on the device of the forward pass. Null channels have zero gradient.
template <class T>
struct GBufferGradT {
  const T* color = nullptr;
  const T* alpha = nullptr;
  const T* depth = nullptr;
  const T* median_depth = nullptr;
  const T* normal = nullptr;
  const T* extras = nullptr;
};

// What the forward pass keeps for the backward pass (all on `device`). Read-only for callers; `radii` is
// also the visibility mask densification counts with.
template <class T>
struct RasterStateT {
  Camera camera;
  RasterSettings settings;
  Device device = Device::CPU;
  int count = 0, sh_degree = 0, n_extras = 0;
  int tiles_x = 0, tiles_y = 0;
  std::size_t n_instances = 0;

  // Per Gaussian.
  Buffer<std::int32_t> radii;       // pixels; 0 = culled (behind near plane, degenerate or off screen)
  Buffer<T> means2d;                // [N][2] pixels
  Buffer<T> conics;                 // [N][3] (a, b, c) of the inverse dilated 2D covariance
  Buffer<T> opacities;              // [N] sigmoid(logit) * 3D and 2D filter compensations
  Buffer<T> colors;                 // [N][3] SH colour (+0.5, clamped at 0)
  Buffer<T> depths;                 // [N] camera-space z of the centre
  Buffer<T> depth_planes;           // [N][2] dz/du, dz/dv of the ray-space depth plane
  Buffer<T> normals;                // [N][3] camera-space unit normal of the depth plane, facing the camera
  Buffer<T> packed;                 // [N][16] the above in one cache line per Gaussian, for the blend loops
  Buffer<std::uint32_t> offsets;    // [N] first instance slot of each Gaussian (exclusive scan of tiles touched)
  Buffer<std::int32_t> tile_rects;  // [N][4] tile rectangle x0, y0, x1, y1 (exclusive ends)

  // Per (tile, Gaussian) instance, sorted by (tile, depth).
  Buffer<std::uint32_t> sorted_gauss;  // Gaussian index
  Buffer<std::uint32_t> sorted_slot;   // unsorted instance slot (offsets[g] + k): where per-tile partial gradients go
  Buffer<std::uint32_t> tile_ranges;   // [tiles][2] begin, end into the sorted instances

  // Per pixel.
  Buffer<T> final_T;                  // transmittance after the last contributor
  Buffer<std::uint32_t> n_contrib;    // one past the sorted index of the last contributor (tile begin if none)
  Buffer<std::uint32_t> median_index; // sorted index of the median-depth contributor, kNoContributor if none

  // Stage times in ms of the last forward / backward pass, when settings.profile is set.
  struct StageTimes {
    double preprocess = 0, binning = 0, blend = 0, backward_blend = 0, backward_gaussians = 0;
  };
  mutable StageTimes times;
};

constexpr std::uint32_t kNoContributor = 0xffffffffu;

}  // namespace goris
