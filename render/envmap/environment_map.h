#pragma once
// The learnable environment light (docs/design/conventions.md, Environment map): a cube map of 6 x R x R RGB
// texels stored as log radiance (texel = exp(parameter), see cube_map_ops.h for why), prefiltered into a
// roughness-indexed mip chain (split-sum style) that shading kernels sample with cube_lookup
// (cube_map_math.h).
//
//   EnvironmentMap env(256, Device::CPU);
//   env.update();                               // after every change of params(): rebuild the mip chain
//   ... shading reads env.mips(), its backward adds into env.mip_grads() ...
//   env.backward();                             // grads() += dL/dparams; mip_grads() is consumed (zeroed)
//   ... optimiser steps params() with grads(), then env.zero_grad() ...
#include <cstddef>
#include <vector>

#include "core/compute/buffer.h"
#include "render/envmap/cube_map_math.h"

namespace goris {

class EnvironmentMap {
 public:
  // resolution: texels per face side, a power of two in [1, 4096]; levels: mip levels down from it
  // (0 = all the way to 1x1, i.e. log2(R) + 1); initial_radiance: the value every texel starts at.
  EnvironmentMap(int resolution, Device device, float initial_radiance = 0.5f, int levels = 0);

  int resolution() const { return res_; }
  int levels() const { return levels_; }
  Device device() const { return params_.device(); }
  std::size_t param_count() const { return params_.size(); }  // 6 R R 3

  Buffer<float>& params() { return params_; }  // log radiance [6][R][R][3]: the optimiser's parameter
  const Buffer<float>& params() const { return params_; }
  Buffer<float>& grads() { return grads_; }  // dL/dparams, accumulated by backward()
  const Buffer<float>& grads() const { return grads_; }

  // Rebuilds the activated mip chain from params(). Throws goris::Error for non-finite parameters (checked
  // on the CPU backend only, as everywhere in the engine).
  void update();
  // View of the activated chain for lookups (valid until the next update() or move).
  envmap::CubeMipsT<float> mips() const { return {chain_.data(), res_, levels_}; }
  // Where lookups add dL/dtexel, same layout as the chain. Zeroed by backward() and zero_grad().
  float* mip_grads() { return chain_grad_.data(); }

  // Folds mip_grads() through the prefilter adjoint and the activation into grads() (+=), then zeroes
  // mip_grads() so the next iteration starts clean.
  void backward();
  void zero_grad();

  // Batched lookups (pointers on device()): out[i] = radiance seen in direction dirs[i] at roughness[i].
  void lookup(const float* dirs, const float* roughness, std::size_t n, float* out) const;
  // Backward of lookup: mip_grads() += dL/dtexels; ddirs / droughness written where not null.
  void lookup_backward(const float* dirs, const float* roughness, const float* dout, std::size_t n, float* ddirs,
                       float* droughness);

  // Host image of the sharp (level 0) map in equirectangular form, [height = width / 2][width][3] linear
  // radiance; longitude around +Y (the up axis of OpenCV-world scenes is scene-dependent, so this is a
  // preview, not a standard). Needs update() to have run.
  std::vector<float> equirect_image(int width) const;

 private:
  int res_ = 0, levels_ = 0;
  Buffer<float> params_, grads_, chain_, chain_grad_, scratch_;
};

}  // namespace goris
