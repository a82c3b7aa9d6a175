#pragma once
// Non-owning view of a Gaussian scene's per-Gaussian parameters, as renderers read them. All pointers
// live on one device. Values are stored BEFORE activation (docs/design/conventions.md), except `extras`,
// which the scene model activates (sigmoid) before rendering so that renderers blend plain values.
//
// Layouts (row-major, N = count):
//   positions       [N][3]
//   log_scales      [N][3]      scale = exp(log_scale)
//   rotations       [N][4]      quaternion (w, x, y, z), not necessarily normalised
//   opacity_logits  [N]         opacity = sigmoid(logit)
//   sh              [N][16][3]  SH coefficients, coefficient-major (k = 0 is DC), colour = SH + 0.5,
//                               clamped at 0; only the first (sh_degree + 1)^2 coefficients are used
//   extras          [N][n_extras]  activated extra channels (diffuse rgb, F0 rgb, roughness, region, label...)
//   filter3d_var    [N]         Mip-Splatting 3D filter variance in world units^2 (null: no 3D filter)
// Gradients use the same layouts.
namespace goris {

constexpr int kMaxShCoeffs = 16;  // degree 3

struct GaussianView {
  int count = 0;
  const float* positions = nullptr;
  const float* log_scales = nullptr;
  const float* rotations = nullptr;
  const float* opacity_logits = nullptr;
  const float* sh = nullptr;
  int sh_degree = 0;
  const float* extras = nullptr;
  int n_extras = 0;
  const float* filter3d_var = nullptr;
};

// Where gradients with respect to the same parameters are accumulated (+=); null pointers are skipped.
struct GaussianGradView {
  float* positions = nullptr;
  float* log_scales = nullptr;
  float* rotations = nullptr;
  float* opacity_logits = nullptr;
  float* sh = nullptr;
  float* extras = nullptr;
  // |d loss / d mean2d| per Gaussian (pixels), summed over calls: the densification statistic.
  float* mean2d_grad_norm = nullptr;
};

}  // namespace goris
