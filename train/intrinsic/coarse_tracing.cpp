// Public entry points of coarse tracing: validate, then run coarse_tracing_ops.h on the CPU or its CUDA twin.
#include "train/intrinsic/coarse_tracing.h"

#include <string>

#include "core/compute/cuda_dispatch.h"
#include "core/util/error.h"
#include "train/intrinsic/coarse_tracing_cuda.h"
#include "train/intrinsic/coarse_tracing_ops.h"

namespace goris {

namespace {

constexpr const char* kWho = "coarse tracing";

void check_image(int width, int height) {
  if (width <= 0 || height <= 0) throw Error(kWho, "image size is empty");
}

// The ray list itself: sizes agree, and (on the CPU, where it is cheap) every pixel lies in the image.
void check_rays(const ReflectionRays& rays, int width, int height) {
  check_image(width, height);
  const std::size_t n = rays.count;
  if (rays.pixels.size() != n || rays.origins.size() != 3 * n || rays.directions.size() != 3 * n)
    throw Error(kWho, "ray list of " + std::to_string(n) + " rays has lists of other lengths");
  const Device d = rays.pixels.device();
  if (rays.origins.device() != d || rays.directions.device() != d)
    throw Error(kWho, "ray list lives on more than one device");
  if (d != Device::CPU) return;
  const std::size_t P = std::size_t(width) * std::size_t(height);
  for (std::size_t i = 0; i < n; ++i)
    if (rays.pixels[i] >= P)
      throw Error(kWho, "ray pixel index outside the " + std::to_string(width) + "x" + std::to_string(height) + " image");
}

void check_selection(const RaySelection& s, std::size_t n, Device d, const char* what) {
  if (s.keep.size() != n || s.slot.size() != n || s.keep.device() != d || s.slot.device() != d)
    throw Error(kWho, std::string(what) + " does not belong to a list of " + std::to_string(n) + " rays on " +
                          device_name(d));
}

RaySelection with_slots(Buffer<std::uint32_t> keep) {
  RaySelection s;
  s.slot = Buffer<std::uint32_t>(keep.size(), keep.device());
  s.count = coarse::scan_count(keep, s.slot);
  s.keep = std::move(keep);
  return s;
}

}  // namespace

RaySelection select_block_rays(const ReflectionRays& rays, int width, int height, const Buffer<float>* rs,
                               const CoarseTracingSettings& st) {
  check_rays(rays, width, height);
  if (st.levels < 2 || st.levels > ssf::kMaxLevels)
    throw Error(kWho, "levels must lie in [2, " + std::to_string(ssf::kMaxLevels) + "], got " + std::to_string(st.levels));
  if (st.max_level < 0 || st.max_level > st.levels - 2)
    throw Error(kWho, "max_level must lie in [0, levels - 2 = " + std::to_string(st.levels - 2) + "], got " +
                          std::to_string(st.max_level));
  const Device d = rays.pixels.device();
  const std::size_t P = std::size_t(width) * std::size_t(height), n = rays.count;
  if (rs && (rs->size() != P || rs->device() != d))
    throw Error(kWho, "screen roughness has " + std::to_string(rs->size()) + " values on " + device_name(rs->device()) +
                          ", expected " + std::to_string(P) + " on " + device_name(d));
  Buffer<std::uint32_t> keep(n, d);
  Buffer<std::int32_t> lvl(P, d);
  const float* r = rs ? rs->data() : nullptr;
  if (d == Device::CPU)
    coarse::select<Device::CPU>(rays.pixels.data(), n, width, height, r, st.levels, st.max_level, st.seed, lvl.data(),
                                keep.data());
  else
    GORIS_CUDA_CALL(kWho, coarse::cuda::select(rays.pixels.data(), n, width, height, r, st.levels, st.max_level,
                                               st.seed, lvl.data(), keep.data()));
  return with_slots(std::move(keep));
}

RaySelection selection_difference(const RaySelection& a, const RaySelection& b) {
  const std::size_t n = a.keep.size();
  const Device d = a.keep.device();
  check_selection(a, n, d, "first selection");
  check_selection(b, n, d, "second selection");
  Buffer<std::uint32_t> keep(n, d);
  if (d == Device::CPU)
    coarse::difference<Device::CPU>(a.keep.data(), b.keep.data(), n, keep.data());
  else
    GORIS_CUDA_CALL(kWho, coarse::cuda::difference(a.keep.data(), b.keep.data(), n, keep.data()));
  return with_slots(std::move(keep));
}

void gather_rays(const ReflectionRays& rays, const RaySelection& sel, ReflectionRays& out, std::size_t offset) {
  const std::size_t n = rays.count;
  const Device d = rays.pixels.device();
  check_selection(sel, n, d, "ray selection");
  if (out.pixels.device() != d || out.origins.device() != d || out.directions.device() != d)
    throw Error(kWho, "gathered rays go to another device than the ray list's");
  const std::size_t end = offset + sel.count;
  if (out.pixels.size() < end || out.origins.size() < 3 * end || out.directions.size() < 3 * end)
    throw Error(kWho, "output ray list holds " + std::to_string(out.pixels.size()) + " rays, " + std::to_string(end) +
                          " needed");
  if (n == 0) return;
  if (d == Device::CPU)
    coarse::gather<Device::CPU>(rays.pixels.data(), rays.origins.data(), rays.directions.data(), n, sel.keep.data(),
                                sel.slot.data(), offset, out.pixels.data(), out.origins.data(), out.directions.data());
  else
    GORIS_CUDA_CALL(kWho, coarse::cuda::gather(rays.pixels.data(), rays.origins.data(), rays.directions.data(), n,
                                               sel.keep.data(), sel.slot.data(), offset, out.pixels.data(),
                                               out.origins.data(), out.directions.data()));
}

Buffer<float> representative_distance(const ReflectionRays& rays, const RaySelection* sel, const Buffer<float>& depth,
                                      const Buffer<float>& alpha, int width, int height, int block_level,
                                      float extent) {
  check_rays(rays, width, height);
  const std::size_t n = rays.count, P = std::size_t(width) * std::size_t(height);
  const Device d = rays.pixels.device();
  if (sel) check_selection(*sel, n, d, "ray selection");
  const std::size_t traced = sel ? sel->count : n;
  if (depth.size() != traced || alpha.size() != traced || depth.device() != d || alpha.device() != d)
    throw Error(kWho, "traced depth / alpha do not hold the " + std::to_string(traced) + " selected rays on " +
                          device_name(d));
  if (block_level < 0 || block_level > 12) throw Error(kWho, "block level must lie in [0, 12]");
  if (!(extent > 0)) throw Error(kWho, "the scene extent must be positive");
  Buffer<float> out(P, d);
  Buffer<std::uint32_t> index(P, d);
  const std::uint32_t* keep = sel ? sel->keep.data() : nullptr;
  const std::uint32_t* slot = sel ? sel->slot.data() : nullptr;
  if (d == Device::CPU)
    coarse::representative_distance<Device::CPU>(rays.pixels.data(), n, width, height, keep, slot, depth.data(),
                                                 alpha.data(), block_level, extent, index.data(), out.data());
  else
    GORIS_CUDA_CALL(kWho, coarse::cuda::representative_distance(rays.pixels.data(), n, width, height, keep, slot,
                                                                depth.data(), alpha.data(), block_level, extent,
                                                                index.data(), out.data()));
  return out;
}

Buffer<float> selection_mass(const ReflectionRays& rays, const RaySelection& sel, int width, int height) {
  check_rays(rays, width, height);
  const Device d = rays.pixels.device();
  check_selection(sel, rays.count, d, "ray selection");
  const std::size_t P = std::size_t(width) * std::size_t(height);
  Buffer<float> out(P, d);
  if (d == Device::CPU)
    coarse::mass<Device::CPU>(rays.pixels.data(), rays.count, sel.keep.data(), P, out.data());
  else
    GORIS_CUDA_CALL(kWho, coarse::cuda::mass(rays.pixels.data(), rays.count, sel.keep.data(), P, out.data()));
  return out;
}

}  // namespace goris
