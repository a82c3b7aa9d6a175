#include "render/ssf/glossy_filter.h"

#include <string>
#include <type_traits>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/memory.h"
#include "render/ssf/pyramid_passes.h"
#include "render/ssf/ssf_checks.h"
#include "render/ssf/ssf_cuda.h"

namespace goris::ssf {

namespace {

constexpr const char* kOp = "glossy filter";

template <class T>
PyramidPtrs<T> ptrs(std::vector<Buffer<T>>& image, std::vector<Buffer<T>>& normal, std::vector<Buffer<T>>& inv,
                    std::vector<Buffer<T>>& mass, std::vector<Buffer<T>>& norm, const std::vector<LevelDims>& dims,
                    int channels, int power) {
  PyramidPtrs<T> p;
  p.levels = int(dims.size());
  p.channels = channels;
  p.power = power;
  for (int k = 0; k < p.levels; ++k) {
    p.d[k] = dims[size_t(k)];
    p.image[k] = image[size_t(k)].data();
    if (!normal.empty()) p.normal[k] = normal[size_t(k)].data();
    if (!inv.empty()) p.inv_sum[k] = inv[size_t(k)].data();
    if (!mass.empty()) p.mass[k] = mass[size_t(k)].data();
    if (!norm.empty() && k > 0) p.norm[k] = norm[size_t(k)].data();
  }
  return p;
}

// Buffers of the right size on the right device, reusing the old ones when they fit (training calls this
// every iteration with the same sizes).
template <class T>
void ensure(Buffer<T>& b, size_t n, Device d) {
  if (b.size() != n || b.device() != d) b = Buffer<T>(n, d);
}

}  // namespace

template <class T>
GlossyFilter<T>::GlossyFilter(PyramidConfig cfg) : cfg_(cfg) {
  if (cfg.levels < 2 || cfg.levels > kMaxLevels)
    throw Error(kOp, "levels must be in [2, " + std::to_string(kMaxLevels) + "], got " + std::to_string(cfg.levels));
  if (cfg.normal_power < 0 || cfg.normal_power > 64)
    throw Error(kOp, "normal_power must be in [0, 64], got " + std::to_string(cfg.normal_power));
}

template <class T>
void GlossyFilter<T>::forward(const Buffer<T>& x, int channels, int height, int width, const Buffer<T>& normals,
                              const Buffer<T>& rs, Buffer<T>& out, const Buffer<T>* mass) {
  if (channels < 1 || height < 1 || width < 1)
    throw Error(kOp, "image shape " + std::to_string(channels) + "x" + std::to_string(height) + "x" +
                         std::to_string(width) + " is empty");
  const Device d = x.device();
  if (d == Device::CUDA && !std::is_same_v<T, float>) throw Error(kOp, "double precision runs on the CPU only");
  const size_t plane = size_t(height) * size_t(width);
  check_buffer(kOp, "input image", x, size_t(channels) * plane, d);
  check_buffer(kOp, "normal image", normals, 3 * plane, d);
  check_buffer(kOp, "screen roughness", rs, plane, d);
  check_finite(kOp, "input image", x);
  check_finite(kOp, "normal image", normals);
  check_finite(kOp, "screen roughness", rs);
  if (mass) {
    check_buffer(kOp, "mass image", *mass, plane, d);
    check_finite(kOp, "mass image", *mass);
    check_non_negative(kOp, "mass image", *mass);
  }

  device_ = d;
  channels_ = channels;
  weighted_ = mass != nullptr;
  dims_.assign(size_t(cfg_.levels), LevelDims{});
  dims_[0] = LevelDims{height, width};
  for (int k = 1; k < cfg_.levels; ++k)
    dims_[size_t(k)] = LevelDims{(dims_[size_t(k - 1)].h + 1) / 2, (dims_[size_t(k - 1)].w + 1) / 2};
  image_.resize(dims_.size());
  normal_.resize(dims_.size());
  inv_sum_.resize(dims_.size());
  mass_.resize(weighted_ ? dims_.size() : 0);
  norm_.resize(weighted_ ? dims_.size() : 0);
  for (size_t k = 0; k < dims_.size(); ++k) {
    const size_t m = size_t(dims_[k].h) * size_t(dims_[k].w);
    ensure(image_[k], size_t(channels) * m, d);
    ensure(normal_[k], 3 * m, d);
    ensure(inv_sum_[k], m, d);
    if (weighted_) ensure(mass_[k], m, d);
    if (weighted_ && k > 0) ensure(norm_[k], plane, d);
  }
  ensure(rs_, plane, d);
  device_copy(image_[0].data(), d, x.data(), d, x.bytes());
  if (weighted_) device_copy(mass_[0].data(), d, mass->data(), d, mass->bytes());
  device_copy(rs_.data(), d, rs.data(), d, rs.bytes());
  ensure(out, size_t(channels) * plane, d);

  const PyramidPtrs<T> P = ptrs(image_, normal_, inv_sum_, mass_, norm_, dims_, channels, cfg_.normal_power);
  if (d == Device::CPU) {
    normalise_normals<Device::CPU>(normals.data(), P.normal[0], plane);
    build_levels<Device::CPU>(P);
    sample_all<Device::CPU>(P, rs_.data(), out.data());
  } else if constexpr (std::is_same_v<T, float>) {
    GORIS_CUDA_CALL(kOp, cuda::normalise_normals(normals.data(), P.normal[0], plane));
    GORIS_CUDA_CALL(kOp, cuda::build_levels(P));
    GORIS_CUDA_CALL(kOp, cuda::sample_all(P, rs_.data(), out.data()));
  }
}

template <class T>
void GlossyFilter<T>::backward(const Buffer<T>& grad_out, Buffer<T>* grad_x, Buffer<T>* grad_rs) {
  if (dims_.empty()) throw Error(kOp, "backward() called before forward()");
  const Device d = device_;
  const size_t plane = size_t(dims_[0].h) * size_t(dims_[0].w);
  check_buffer(kOp, "output gradient", grad_out, size_t(channels_) * plane, d);
  if (grad_x) check_buffer(kOp, "input gradient", *grad_x, size_t(channels_) * plane, d);
  if (grad_rs) check_buffer(kOp, "screen roughness gradient", *grad_rs, plane, d);
  std::vector<Buffer<T>> none;
  const PyramidPtrs<T> P = ptrs(image_, normal_, inv_sum_, mass_, norm_, dims_, channels_, cfg_.normal_power);
  if (grad_rs) {
    if (d == Device::CPU)
      backward_rs<Device::CPU>(P, rs_.data(), grad_out.data(), grad_rs->data());
    else if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL(kOp, cuda::backward_rs(P, rs_.data(), grad_out.data(), grad_rs->data()));
  }
  if (!grad_x) return;
  grad_scratch_.resize(dims_.size());
  for (size_t k = 0; k < dims_.size(); ++k) ensure(grad_scratch_[k], image_[k].size(), d);
  const PyramidPtrs<T> S = ptrs(grad_scratch_, none, none, none, none, dims_, channels_, cfg_.normal_power);
  if (d == Device::CPU)
    backward_x<Device::CPU>(P, S, rs_.data(), grad_out.data(), grad_x->data());
  else if constexpr (std::is_same_v<T, float>)
    GORIS_CUDA_CALL(kOp, cuda::backward_x(P, S, rs_.data(), grad_out.data(), grad_x->data()));
}

template <class T>
const Buffer<T>& GlossyFilter<T>::mass(int k) const {
  if (!weighted_) throw Error(kOp, "mass() asked of an unweighted pyramid");
  return mass_.at(size_t(k));
}

template class GlossyFilter<float>;
template class GlossyFilter<double>;

}  // namespace goris::ssf
