#include "train/optimizer/densify.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "core/scene/gaussian_kernels.h"
#include "core/util/error.h"
#include "train/optimizer/train_cuda.h"
#include "train/optimizer/train_kernels.h"

namespace goris {

namespace {

// Counter-based random numbers: the same (seed, Gaussian, child, axis) always gives the same sample, on
// any number of threads.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
float standard_normal(std::uint64_t seed, std::uint64_t i, int child, int axis) {
  const std::uint64_t h1 = splitmix64(seed ^ splitmix64(i * 16 + std::uint64_t(child) * 4 + std::uint64_t(axis)));
  const std::uint64_t h2 = splitmix64(h1);
  const double u1 = (double(h1 >> 11) + 0.5) / 9007199254740992.0;  // (0, 1), 53 bits
  const double u2 = double(h2 >> 11) / 9007199254740992.0;
  return float(std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
}

glm::mat3 rotation_matrix(const float* q4) {
  glm::vec4 q(q4[0], q4[1], q4[2], q4[3]);
  const float len = glm::length(q);
  q = len > 0 ? q / len : glm::vec4(1, 0, 0, 0);
  const float w = q[0], x = q[1], y = q[2], z = q[3];
  glm::mat3 R;  // column-major: R[col][row]
  R[0] = glm::vec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
  R[1] = glm::vec3(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
  R[2] = glm::vec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
  return R;
}

// What becomes of row src in the rebuilt model.
enum RowKind : std::uint8_t { kKeep = 0, kClone = 1, kChild = 2 };

struct NewRow {
  std::uint32_t src;
  std::uint8_t kind;
  std::uint8_t child;  // child index for kChild
};

// Replaces model's rows by rows[j] (CPU model): values copied from the source row, moments copied for
// kept rows and zero for new ones, gradients zero.
void rebuild(GaussianModel& model, const std::vector<NewRow>& rows) {
  GaussianModel out(Device::CPU);
  out.allocate(rows.size());
  out.sh_degree = model.sh_degree;
  out.max_sh_degree = model.max_sh_degree;
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& a = model.tensor(Param(p));
    ParamTensor& b = out.tensor(Param(p));
    const size_t w = size_t(a.width);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rows.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t j = r.begin(); j != r.end(); ++j) {
        const size_t s = rows[j].src;
        std::copy_n(a.value.data() + s * w, w, b.value.data() + j * w);
        if (rows[j].kind == kKeep) {
          std::copy_n(a.adam_m.data() + s * w, w, b.adam_m.data() + j * w);
          std::copy_n(a.adam_v.data() + s * w, w, b.adam_v.data() + j * w);
        }
      }
    });
  }
  if (model.filter3d_var.size() == model.count()) {
    out.filter3d_var = Buffer<float>(rows.size(), Device::CPU);
    for (size_t j = 0; j < rows.size(); ++j) out.filter3d_var[j] = model.filter3d_var[rows[j].src];
  }
  model = std::move(out);
}

DensifyStats stats_on_host(const DensifyStats& s) {
  DensifyStats h;
  h.grad_accum = s.grad_accum.copy_to(Device::CPU);
  h.denom = s.denom.copy_to(Device::CPU);
  h.max_radii = s.max_radii.copy_to(Device::CPU);
  return h;
}

}  // namespace

void DensifyStats::reset(size_t n, Device d) {
  for (Buffer<float>* b : {&grad_accum, &denom, &max_radii}) {
    if (b->size() != n || b->device() != d) *b = Buffer<float>(n, d);
    b->fill_zero();
  }
}

void DensifyStats::add_view(const float* view_grad_norm, const std::int32_t* radii, float ndc_scale, size_t n,
                            Device d) {
  if (grad_accum.size() != n) throw Error("DensifyStats::add_view: statistics sized for a different Gaussian count");
  float* acc = grad_accum.data();
  float* den = denom.data();
  float* mr = max_radii.data();
  if (d == Device::CPU) {
    parallel_for(
        Device::CPU, n,
        [=](size_t i) { kernels::densify_stats_add(view_grad_norm, radii, ndc_scale, acc, den, mr, i); }, 2048);
  } else {
    GORIS_CUDA_CALL("densify", detail::densify_stats_add_cuda(view_grad_norm, radii, ndc_scale, acc, den, mr, n));
  }
}

float ndc_gradient_scale(int width, int height) { return 0.5f * std::sqrt(float(width) * float(height)); }

DensifyCounts densify_and_prune(GaussianModel& model, const DensifyStats& stats, const DensifySettings& st,
                                float extent, bool prune_large, std::uint64_t seed) {
  if (model.device() != Device::CPU) {
    GaussianModel host = model.copy_to(Device::CPU);
    const DensifyCounts c = densify_and_prune(host, stats_on_host(stats), st, extent, prune_large, seed);
    model = host.copy_to(model.device());
    return c;
  }
  const size_t n = model.count();
  if (stats.grad_accum.size() != n || stats.denom.size() != n || stats.max_radii.size() != n)
    throw Error("densify_and_prune: statistics sized for a different Gaussian count");
  if (st.split_count < 1) throw Error("densify_and_prune: split_count must be at least 1");
  DensifyCounts counts;
  counts.before = n;

  const float* ls = model.values(Param::LogScale);
  const float* opl = model.values(Param::OpacityLogit);
  const float clone_limit = st.percent_dense * extent;
  const float world_limit = st.max_world_scale * extent;
  const float split_shrink = std::log(0.8f * float(st.split_count));
  // Per Gaussian: does it survive (0/1), how many new rows it makes, and what they are.
  Buffer<std::uint32_t> keep_n(n, Device::CPU), new_n(n, Device::CPU);
  std::vector<std::uint8_t> action(n, 0), child_mask(n, 0);
  parallel_for(Device::CPU, n, [&](size_t i) {
    const float g = stats.denom[i] > 0 ? stats.grad_accum[i] / stats.denom[i] : 0.0f;
    const float max_ls = std::max(ls[i * 3], std::max(ls[i * 3 + 1], ls[i * 3 + 2]));
    const float max_scale = std::exp(max_ls);
    const bool low = kernels::sigmoid(opl[i]) < st.min_opacity;
    const bool too_big = prune_large && ((st.max_screen_radius > 0 && stats.max_radii[i] > st.max_screen_radius) ||
                                         (st.max_world_scale > 0 && max_scale > world_limit));
    const bool selected = g >= st.grad_threshold;
    if (selected && max_scale > clone_limit) {
      action[i] = kChild;
      const bool child_too_big = prune_large && st.max_world_scale > 0 && std::exp(max_ls - split_shrink) > world_limit;
      std::uint8_t mask = 0;
      if (!low && !child_too_big) mask = std::uint8_t((1u << st.split_count) - 1u);
      child_mask[i] = mask;
      keep_n[i] = 0;
      new_n[i] = std::uint32_t(__builtin_popcount(mask));
    } else {
      const bool prune = low || too_big;
      keep_n[i] = prune ? 0 : 1;
      new_n[i] = selected && !prune ? 1 : 0;
      action[i] = selected ? kClone : kKeep;
    }
  });
  Buffer<std::uint32_t> keep_off(n, Device::CPU), new_off(n, Device::CPU);
  exclusive_scan(keep_n, keep_off);
  exclusive_scan(new_n, new_off);
  const size_t total_keep = n ? keep_off[n - 1] + keep_n[n - 1] : 0;
  const size_t total_new = n ? new_off[n - 1] + new_n[n - 1] : 0;

  std::vector<NewRow> rows(total_keep + total_new);
  parallel_for(Device::CPU, n, [&](size_t i) {
    if (keep_n[i]) rows[keep_off[i]] = NewRow{std::uint32_t(i), kKeep, 0};
    size_t j = total_keep + new_off[i];
    if (action[i] == kClone && new_n[i]) rows[j] = NewRow{std::uint32_t(i), kClone, 0};
    if (action[i] == kChild)
      for (int k = 0; k < st.split_count; ++k)
        if (child_mask[i] & (1u << k)) rows[j++] = NewRow{std::uint32_t(i), kChild, std::uint8_t(k)};
  });
  for (size_t i = 0; i < n; ++i) {
    if (action[i] == kClone && new_n[i]) ++counts.cloned;
    if (action[i] == kChild) {
      ++counts.split;
      counts.pruned += size_t(st.split_count) - new_n[i];
    } else if (!keep_n[i]) {
      ++counts.pruned;
    }
  }

  // Split children: positions sampled from the parent's Gaussian, scales shrunk.
  const std::vector<float> parent_pos(model.values(Param::Position), model.values(Param::Position) + n * 3);
  const std::vector<float> parent_rot(model.values(Param::Rotation), model.values(Param::Rotation) + n * 4);
  const std::vector<float> parent_ls(ls, ls + n * 3);
  rebuild(model, rows);
  float* pos = model.values(Param::Position);
  float* nls = model.values(Param::LogScale);
  parallel_for(Device::CPU, rows.size(), [&](size_t j) {
    if (rows[j].kind != kChild) return;
    const size_t s = rows[j].src;
    const glm::mat3 R = rotation_matrix(&parent_rot[s * 4]);
    glm::vec3 local;
    for (int a = 0; a < 3; ++a) local[a] = std::exp(parent_ls[s * 3 + a]) * standard_normal(seed, s, rows[j].child, a);
    const glm::vec3 offset = R * local;
    for (int a = 0; a < 3; ++a) {
      pos[j * 3 + a] = parent_pos[s * 3 + a] + offset[a];
      nls[j * 3 + a] = parent_ls[s * 3 + a] - split_shrink;
    }
  });
  counts.after = model.count();
  return counts;
}

size_t prune_gaussians(GaussianModel& model, const std::vector<std::uint8_t>& keep) {
  if (keep.size() != model.count()) throw Error("prune_gaussians: mask size differs from the Gaussian count");
  if (model.device() != Device::CPU) {
    GaussianModel host = model.copy_to(Device::CPU);
    const size_t removed = prune_gaussians(host, keep);
    model = host.copy_to(model.device());
    return removed;
  }
  const size_t n = keep.size();
  Buffer<std::uint32_t> flags(n, Device::CPU), offs(n, Device::CPU);
  for (size_t i = 0; i < n; ++i) flags[i] = keep[i] ? 1 : 0;
  exclusive_scan(flags, offs);
  const size_t kept = n ? offs[n - 1] + flags[n - 1] : 0;
  std::vector<NewRow> rows(kept);
  parallel_for(Device::CPU, n, [&](size_t i) {
    if (flags[i]) rows[offs[i]] = NewRow{std::uint32_t(i), kKeep, 0};
  });
  rebuild(model, rows);
  return n - kept;
}

void reset_opacity(GaussianModel& model, float max_opacity) {
  const float cap = kernels::logit(max_opacity);
  if (model.device() != Device::CPU) {
    GaussianModel host = model.copy_to(Device::CPU);
    reset_opacity(host, max_opacity);
    model = host.copy_to(model.device());
    return;
  }
  ParamTensor& t = model.tensor(Param::OpacityLogit);
  float* o = t.value.data();
  // min(sigmoid(x), cap) in logit space is min(x, logit(cap)): sigmoid is monotonic.
  parallel_for(Device::CPU, model.count(), [=](size_t i) { o[i] = std::min(o[i], cap); });
  t.adam_m.fill_zero();
  t.adam_v.fill_zero();
}

}  // namespace goris
