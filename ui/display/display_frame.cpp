#include "ui/display/display_frame.h"

#include <algorithm>
#include <cmath>

#include "core/compute/memory.h"
#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "ui/display/frame_layout.h"

namespace goris::ui {

namespace {

// Planar [C][H][W] channels first..first+count-1 into interleaved [H][W][stride] at column `at`.
void interleave(const std::vector<float>& planar, int first, int count, size_t hw, std::vector<float>& out, int stride,
                int at) {
  for (int c = 0; c < count; ++c) {
    const float* src = planar.data() + size_t(first + c) * hw;
    for (size_t p = 0; p < hw; ++p) out[p * stride + at + c] = src[p];
  }
}

// The same index rule as goris::depth_to_turbo (render/maps), so the editor's depth colours match
// `goris render --maps`.
float percentile(std::vector<float> v, double q) {
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// Depth (camera z) where the alpha is high enough, and the TURBO map's range from its inverse percentiles.
void set_depth(DisplayFrame& f, const std::vector<float>& alpha, const std::vector<float>& depth) {
  const size_t hw = f.pixels();
  f.depth.assign(hw, 0.0f);
  std::vector<float> inverse;
  inverse.reserve(hw);
  for (size_t p = 0; p < hw; ++p) {
    if (alpha[p] < DisplayFrame::kMinAlpha) continue;
    const float z = depth[p] / alpha[p];
    f.depth[p] = z;
    if (z > 0) inverse.push_back(1.0f / z);
  }
  if (!inverse.empty()) {
    f.inv_depth_near = percentile(inverse, 0.99);
    f.inv_depth_far = percentile(inverse, 0.01);
    if (!(f.inv_depth_near > f.inv_depth_far)) f.inv_depth_near = f.inv_depth_far * 1.01f + 1e-6f;
  }
}

}  // namespace

DisplayFrame make_display_frame(const GBuffer& gb, const Camera& camera) {
  if (gb.color.device() != Device::CPU) return make_device_display_frame(gb, camera);
  DisplayFrame f;
  f.camera = camera;
  f.width = gb.width;
  f.height = gb.height;
  const size_t hw = gb.pixels();
  const std::vector<float> color = gb.color.to_host(), normal = gb.normal.to_host();
  f.alpha = gb.alpha.to_host();
  const std::vector<float>& alpha = f.alpha;
  f.color.assign(hw * 3, 0.0f);
  interleave(color, 0, 3, hw, f.color, 3, 0);

  f.normal.assign(hw * 3, 0.0f);
  for (size_t p = 0; p < hw; ++p) {
    if (alpha[p] < DisplayFrame::kMinAlpha) continue;
    const glm::vec3 n(normal[p], normal[hw + p], normal[2 * hw + p]);
    const float len = glm::length(n);
    if (len > 1e-8f)
      for (int c = 0; c < 3; ++c) f.normal[p * 3 + c] = n[c] / len;
  }
  set_depth(f, alpha, gb.depth.to_host());

  f.diffuse.assign(hw * 3, 0.0f);
  f.fresnel.assign(hw * 3, 0.0f);
  f.misc.assign(hw * 4, 0.0f);
  if (gb.n_extras >= extra::kCount) {
    const std::vector<float> extras = gb.extras.to_host();
    interleave(extras, extra::kDiffuse, 3, hw, f.diffuse, 3, 0);
    interleave(extras, extra::kFresnel, 3, hw, f.fresnel, 3, 0);
    interleave(extras, extra::kRoughness, 1, hw, f.misc, 4, 0);
    interleave(extras, extra::kRegion, 1, hw, f.misc, 4, 1);
    interleave(extras, extra::kLabel, 1, hw, f.misc, 4, 2);
  }
  for (size_t p = 0; p < hw; ++p) f.misc[p * 4 + 3] = alpha[p];
  return f;
}

DisplayFrame make_device_display_frame(const GBuffer& gb, const Camera& camera) {
  namespace fl = frame_layout;
  DisplayFrame f;
  f.camera = camera;
  f.width = gb.width;
  f.height = gb.height;
  const size_t hw = gb.pixels();
  const Device d = gb.color.device();
  DeviceImages& g = f.gpu;
  for (Buffer<float>* b : {&g.color, &g.normal, &g.diffuse, &g.fresnel, &g.misc}) *b = Buffer<float>(hw * 4, d);
  fl::interleave(d, gb.color.data(), 0, 3, hw, g.color.data(), 4, 0);
  fl::unit_normals(d, gb.normal.data(), gb.alpha.data(), hw, DisplayFrame::kMinAlpha, g.normal.data(), 4);
  const bool extras = gb.n_extras >= extra::kCount;
  if (extras) {
    fl::interleave(d, gb.extras.data(), extra::kDiffuse, 3, hw, g.diffuse.data(), 4, 0);
    fl::interleave(d, gb.extras.data(), extra::kFresnel, 3, hw, g.fresnel.data(), 4, 0);
    fl::interleave(d, gb.extras.data(), extra::kRoughness, 1, hw, g.misc.data(), 4, 0);
    fl::interleave(d, gb.extras.data(), extra::kRegion, 1, hw, g.misc.data(), 4, 1);
    fl::interleave(d, gb.extras.data(), extra::kLabel, 1, hw, g.misc.data(), 4, 2);
  } else {
    for (Buffer<float>* b : {&g.diffuse, &g.fresnel, &g.misc}) b->fill_zero();
  }
  fl::interleave(d, gb.alpha.data(), 0, 1, hw, g.misc.data(), 4, 3);
  for (Buffer<float>* b : {&g.color, &g.normal, &g.diffuse, &g.fresnel}) fl::fill(d, b->data(), hw, 4, 3, 1.0f);
  // The host needs depth and alpha (picking, the depth range); the copies also wait for the passes above.
  f.alpha = gb.alpha.to_host();
  set_depth(f, f.alpha, gb.depth.to_host());
  return f;
}

void add_intrinsic_maps(DisplayFrame& f, const IntrinsicMaps& m) {
  const size_t hw = f.pixels();
  if (m.width != f.width || m.height != f.height || m.color.size() != 3 * hw || m.glossy.size() != 3 * hw ||
      m.indirect.size() != 3 * hw || m.env.size() != 3 * hw || m.visibility.size() != hw)
    throw Error("display", "the intrinsic maps (" + std::to_string(m.width) + "x" + std::to_string(m.height) +
                               ") do not match the frame (" + std::to_string(f.width) + "x" +
                               std::to_string(f.height) + ")");
  // The maps are host images: on a CUDA frame the shaded colour replaces the device colour on the host.
  f.gpu.color = Buffer<float>();
  f.color.resize(hw * 3);
  interleave(m.color, 0, 3, hw, f.color, 3, 0);
  for (std::vector<float>* v : {&f.glossy, &f.indirect, &f.env}) v->assign(hw * 3, 0.0f);
  interleave(m.glossy, 0, 3, hw, f.glossy, 3, 0);
  interleave(m.indirect, 0, 3, hw, f.indirect, 3, 0);
  std::vector<float> lit;
  for (size_t p = 0; p < hw; ++p) {
    const float v = std::max({f.indirect[p * 3], f.indirect[p * 3 + 1], f.indirect[p * 3 + 2]});
    if (v > 0) lit.push_back(v);
  }
  f.indirect_gain = 1.0f;
  if (!lit.empty()) f.indirect_gain = std::clamp(1.0f / std::max(percentile(lit, 0.99), 1e-6f), 1.0f, DisplayFrame::kMaxIndirectGain);
  interleave(m.env, 0, 3, hw, f.env, 3, 0);
  f.light.assign(hw * 2, 0.0f);
  interleave(m.visibility, 0, 1, hw, f.light, 2, 0);
  f.screen_roughness = m.screen_roughness.size() == hw;
  if (f.screen_roughness) interleave(m.screen_roughness, 0, 1, hw, f.light, 2, 1);
  f.traced.clear();
  if (f.screen_roughness) {  // the filter's maps come with the traced light it filtered
    if (m.indirect_traced.size() != 3 * hw || m.visibility_traced.size() != hw)
      throw Error("display", "the traced L_ind / V maps do not match the frame");
    f.traced.assign(hw * 4, 0.0f);
    interleave(m.indirect_traced, 0, 3, hw, f.traced, 4, 0);
    interleave(m.visibility_traced, 0, 1, hw, f.traced, 4, 3);
  }
}

void add_selection_coverage(DisplayFrame& f, const std::vector<float>& coverage) {
  if (coverage.size() != f.pixels())
    throw Error("display", "the selection coverage has " + std::to_string(coverage.size()) + " pixels, the frame " +
                               std::to_string(f.pixels()));
  f.selection.resize(coverage.size());
  for (size_t p = 0; p < coverage.size(); ++p) f.selection[p] = std::clamp(coverage[p], 0.0f, 1.0f);
}

void add_selection_coverage(DisplayFrame& f, const Buffer<float>& coverage) {
  if (!f.gpu.any() || coverage.device() != f.gpu.misc.device()) return add_selection_coverage(f, coverage.to_host());
  if (coverage.size() != f.pixels())
    throw Error("display", "the selection coverage has " + std::to_string(coverage.size()) + " pixels, the frame " +
                               std::to_string(f.pixels()));
  f.gpu.selection = Buffer<float>(coverage.size(), coverage.device());
  frame_layout::clamp_unit(coverage.device(), coverage.data(), coverage.size(), f.gpu.selection.data());
  device_synchronize(coverage.device());  // the frame goes to the GUI thread complete
}

std::optional<PickResult> pick(const DisplayFrame& f, float u, float v) {
  if (!(u >= 0 && v >= 0 && u < float(f.width) && v < float(f.height))) return std::nullopt;
  PickResult r;
  r.x = std::min(int(u), f.width - 1);
  r.y = std::min(int(v), f.height - 1);
  const size_t p = size_t(r.y) * size_t(f.width) + size_t(r.x);
  r.alpha = f.alpha[p];
  r.depth = f.depth[p];
  r.hit = r.alpha >= DisplayFrame::kMinAlpha && r.depth > 0;
  if (r.hit) {
    const Camera& c = f.camera;
    const glm::vec3 cam((u - c.cx) / c.fx * r.depth, (v - c.cy) / c.fy * r.depth, r.depth);
    r.world = glm::transpose(c.R) * (cam - c.t);
  }
  return r;
}

}  // namespace goris::ui
