#include "render/envmap/environment_map.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_reduce.h>

#include "core/compute/cuda_dispatch.h"
#include "core/util/error.h"
#include "render/envmap/cube_map_ops.h"
#include "render/envmap/environment_map_cuda.h"

namespace goris {

namespace {

const char* kWho = "environment map";

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

int full_levels(int R) {
  int L = 1;
  while ((R >> (L - 1)) > 1) ++L;
  return L;
}

}  // namespace

EnvironmentMap::EnvironmentMap(int resolution, Device device, float initial_radiance, int levels) {
  if (!is_power_of_two(resolution) || resolution > 4096)
    throw Error(kWho, "resolution " + std::to_string(resolution) + " is not a power of two in [1, 4096]");
  const int max_levels = full_levels(resolution);
  if (levels < 0 || levels > max_levels)
    throw Error(kWho, std::to_string(levels) + " mip levels requested; " + std::to_string(resolution) +
                          " texels per face allow 1.." + std::to_string(max_levels) + " (0 = all)");
  if (!(initial_radiance > 0) || !std::isfinite(initial_radiance))
    throw Error(kWho, "initial radiance must be positive and finite (texels are stored as log radiance)");
  res_ = resolution;
  levels_ = levels == 0 ? max_levels : levels;
  const std::size_t n = std::size_t(6) * res_ * res_ * 3;
  std::vector<float> init(n, std::log(initial_radiance));
  params_ = Buffer<float>(init, device);
  grads_ = Buffer<float>(n, device);
  grads_.fill_zero();
  const auto chain = std::size_t(envmap::chain_size(res_, levels_));
  chain_ = Buffer<float>(chain, device);
  chain_grad_ = Buffer<float>(chain, device);
  chain_grad_.fill_zero();
  scratch_ = Buffer<float>(std::max<std::size_t>(1, std::size_t(6) * res_ * (res_ / 2) * 3), device);
  update();
}

void EnvironmentMap::update() {
  if (device() == Device::CUDA) {
    GORIS_CUDA_CALL(kWho, envmap::cuda::build_chain(params_.data(), chain_.data(), scratch_.data(), res_, levels_));
    return;
  }
  const float* p = params_.data();
  const bool finite = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, params_.size()), true,
      [p](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t i = r.begin(); ok && i != r.end(); ++i) ok = std::isfinite(p[i]);
        return ok;
      },
      [](bool a, bool b) { return a && b; });
  if (!finite) throw Error(kWho, "non-finite texel parameter (the optimiser diverged?)");
  envmap::ops::activate(Device::CPU, p, chain_.data(), params_.size());
  envmap::ops::prefilter(Device::CPU, chain_.data(), scratch_.data(), res_, levels_);
}

void EnvironmentMap::backward() {
  if (device() == Device::CUDA) {
    GORIS_CUDA_CALL(kWho, envmap::cuda::backward_chain(chain_grad_.data(), scratch_.data(), chain_.data(),
                                                       grads_.data(), res_, levels_));
  } else {
    envmap::ops::prefilter_adjoint(Device::CPU, chain_grad_.data(), scratch_.data(), res_, levels_);
    envmap::ops::activate_backward(Device::CPU, chain_.data(), chain_grad_.data(), grads_.data(), params_.size());
  }
  chain_grad_.fill_zero();
}

void EnvironmentMap::zero_grad() {
  grads_.fill_zero();
  chain_grad_.fill_zero();
}

void EnvironmentMap::lookup(const float* dirs, const float* roughness, std::size_t n, float* out) const {
  if (n > 0 && (!dirs || !roughness || !out)) throw Error(kWho, "lookup given null arrays");
  if (device() == Device::CUDA)
    GORIS_CUDA_CALL(kWho, envmap::cuda::lookup(mips(), dirs, roughness, n, out));
  else
    envmap::ops::lookup(Device::CPU, mips(), dirs, roughness, n, out);
}

void EnvironmentMap::lookup_backward(const float* dirs, const float* roughness, const float* dout, std::size_t n,
                                     float* ddirs, float* droughness) {
  if (n > 0 && (!dirs || !roughness || !dout)) throw Error(kWho, "lookup backward given null arrays");
  if (device() == Device::CUDA)
    GORIS_CUDA_CALL(kWho, envmap::cuda::lookup_backward(mips(), dirs, roughness, dout, n, chain_grad_.data(), ddirs,
                                                        droughness));
  else
    envmap::ops::lookup_backward(Device::CPU, mips(), dirs, roughness, dout, n, chain_grad_.data(), ddirs,
                                 droughness);
}

std::vector<float> EnvironmentMap::equirect_image(int width) const {
  if (width < 2 || width > 16384) throw Error(kWho, "equirectangular width " + std::to_string(width) + " outside 2..16384");
  const int height = width / 2;
  std::vector<float> level0(std::size_t(6) * res_ * res_ * 3);
  device_copy(level0.data(), Device::CPU, chain_.data(), device(), level0.size() * sizeof(float));
  const envmap::CubeMipsT<float> host{level0.data(), res_, 1};
  std::vector<float> img(std::size_t(width) * height * 3);
  const double pi = 3.14159265358979323846;
  tbb::parallel_for(0, height, [&](int j) {
    const double theta = pi * (j + 0.5) / height;
    for (int i = 0; i < width; ++i) {
      const double phi = 2 * pi * (i + 0.5) / width - pi;
      const envmap::Vec3<float> d(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                                  float(std::sin(theta) * std::cos(phi)));
      const envmap::Vec3<float> c = envmap::cube_lookup(host, d, 0.0f);
      for (int ch = 0; ch < 3; ++ch) img[(std::size_t(j) * width + i) * 3 + ch] = c[ch];
    }
  });
  return img;
}

}  // namespace goris
