#pragma once
// The trainable Gaussian scene: a structure of arrays on one device, every parameter stored BEFORE
// activation (docs/design/conventions.md), each with its gradient and Adam moments beside it. Renderers read
// it through GaussianView / write gradients through GaussianGradView (core/scene/gaussian_view.h); the extra
// material channels are stored as logits here and handed to renderers activated (sigmoid) from a scratch
// buffer, with the chain rule back applied by backprop_extras().
#include <array>
#include <cstddef>
#include <string>

#include "core/compute/buffer.h"
#include "core/scene/gaussian_view.h"

namespace goris {

struct GaussianPly;

// Columns of the extra channels ([N][kExtraCount], logits in the model, sigmoid-activated in views).
namespace extra {
constexpr int kDiffuse = 0;    // 3 channels, RGB
constexpr int kFresnel = 3;    // 3 channels, F0 RGB
constexpr int kRoughness = 6;  // 1
constexpr int kRegion = 7;     // 1: 1 = rough / Lambertian, 0 = glossy
constexpr int kLabel = 8;      // 1: object label
constexpr int kCount = 9;
// PLY property names of the extras, in column order.
extern const std::array<const char*, kCount> kPlyNames;
}  // namespace extra

// The per-Gaussian learnable arrays. The order is the order of serialisation.
enum class Param : int { Position, LogScale, Rotation, OpacityLogit, Sh, ExtraLogit };
constexpr int kParamCount = 6;
const char* param_name(Param p);
int param_width(Param p);  // floats per Gaussian: 3, 3, 4, 1, 48, 9

// One learnable array [count][width] with its gradient and Adam moments (same layout).
struct ParamTensor {
  int width = 0;
  Buffer<float> value, grad, adam_m, adam_v;
};

// Initial values before activation (docs/design/conventions.md, Gaussian parameters and activations).
struct GaussianInit {
  float opacity = 0.1f;
  float diffuse = 0.5f, fresnel = 0.5f, roughness = 0.5f, region = 0.9f, label = 0.5f;
};

class GaussianModel {
 public:
  explicit GaussianModel(Device device = Device::CPU) : device_(device) {}

  Device device() const { return device_; }
  size_t count() const { return count_; }

  // Reallocates every array for n Gaussians: values uninitialised, gradients and moments zero,
  // no 3D filter.
  void allocate(size_t n);
  // A full copy (values, gradients, moments, 3D filter, SH degrees) on device `d`.
  GaussianModel copy_to(Device d) const;

  ParamTensor& tensor(Param p) { return tensors_[int(p)]; }
  const ParamTensor& tensor(Param p) const { return tensors_[int(p)]; }
  float* values(Param p) { return tensor(p).value.data(); }
  const float* values(Param p) const { return tensor(p).value.data(); }
  float* grads(Param p) { return tensor(p).grad.data(); }

  // SH degree used by renderers now (grows during training) and its ceiling.
  int sh_degree = 0;
  int max_sh_degree = 3;

  // Mip-Splatting 3D filter variance per Gaussian ([N], world units^2); empty = no 3D filter.
  Buffer<float> filter3d_var;

  // What renderers read. with_extras activates the extra channels (sigmoid) into a scratch buffer
  // (n_extras = kCount); without, n_extras = 0 and renderers blend no extra channel.
  GaussianView view(bool with_extras);
  // Where renderers accumulate gradients: the parameter gradients, and for the extras an activated-space
  // scratch that backprop_extras() carries back to the logits. mean2d_grad_norm is left null (the
  // densification statistic is owned by the trainer).
  GaussianGradView grad_view(bool with_extras);
  // extras.grad += d(loss)/d(activated extras) * sigmoid'(logit); clears the activated-space scratch.
  void backprop_extras();
  // Zeroes every parameter gradient (and the activated-extras scratch).
  void zero_grad();
  // Sets the diffuse channel to the SH colour's view-independent part (C0 x DC + 1/2 per Gaussian). The
  // shading uses D = the SH colour (C = D + (1 - M) G), so this keeps the channel that maps, the editor,
  // the PLY and the removal's material maps show in step with it instead of at its initial grey.
  void derive_diffuse_from_sh();

  // Builds the model from a PLY (standard 3DGS layout plus optional extras by name: diffuse_0..2,
  // fresnel_0..2, roughness, region, label, all before activation); missing extras take `init`, except a
  // missing diffuse (a standard 3DGS PLY), which is derived from the SH colour (derive_diffuse_from_sh).
  static GaussianModel from_ply(const GaussianPly& ply, Device device, const GaussianInit& init = {});
  // The standard layout at max_sh_degree, extras as named properties (logits), normals zero.
  // bake_3d_filter folds the Mip-Splatting 3D filter into the scales and opacities (scale^2 + var, opacity
  // times sqrt(det S / det(S + var I))) so that viewers without the filter show what the engine renders.
  GaussianPly to_ply(bool bake_3d_filter = false) const;

 private:
  Device device_;
  size_t count_ = 0;
  std::array<ParamTensor, kParamCount> tensors_;
  Buffer<float> extras_activated_, extras_activated_grad_;
};

}  // namespace goris
