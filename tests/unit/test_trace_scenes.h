#pragma once
// Random Gaussian scenes and rays for the tracer tests (any scalar type), the fixture scene of
// ../shared/fixtures/tracer_garden, and a brute-force reference tracer written independently of the
// library's rounds: collect every hit, sort by (t*, index), blend.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <tuple>
#include <vector>

#include "core/io/npy.h"
#include "core/scene/gaussian_view.h"
#include "render/raster/raster_types.h"
#include "render/trace/trace_hit.h"
#include "render/trace/trace_types.h"
#include "render/math/sh.h"

namespace goris::test {

template <class T>
struct SceneArrays {
  int count = 0, sh_degree = 3, n_extras = 0;
  std::vector<T> positions, log_scales, rotations, logits, sh, extras, emit, filter3d;

  GaussiansT<T> view() const {
    GaussiansT<T> g;
    g.count = count;
    g.positions = positions.data();
    g.log_scales = log_scales.data();
    g.rotations = rotations.data();
    g.opacity_logits = logits.data();
    g.sh = sh.data();
    g.sh_degree = sh_degree;
    g.extras = n_extras ? extras.data() : nullptr;
    g.n_extras = n_extras;
    g.filter3d_var = filter3d.empty() ? nullptr : filter3d.data();
    return g;
  }
  const T* emit_or_null() const { return emit.empty() ? nullptr : emit.data(); }

  template <class U>
  SceneArrays<U> cast() const {
    SceneArrays<U> s;
    s.count = count;
    s.sh_degree = sh_degree;
    s.n_extras = n_extras;
    auto cv = [](const std::vector<T>& v) { return std::vector<U>(v.begin(), v.end()); };
    std::tie(s.positions, s.log_scales, s.rotations, s.logits) =
        std::make_tuple(cv(positions), cv(log_scales), cv(rotations), cv(logits));
    std::tie(s.sh, s.extras, s.emit, s.filter3d) = std::make_tuple(cv(sh), cv(extras), cv(emit), cv(filter3d));
    return s;
  }
};

inline GaussianView float_view(const SceneArrays<float>& s) {
  GaussianView v;
  v.count = s.count;
  v.positions = s.positions.data();
  v.log_scales = s.log_scales.data();
  v.rotations = s.rotations.data();
  v.opacity_logits = s.logits.data();
  v.sh = s.sh.data();
  v.sh_degree = s.sh_degree;
  v.extras = s.n_extras ? s.extras.data() : nullptr;
  v.n_extras = s.n_extras;
  v.filter3d_var = s.filter3d.empty() ? nullptr : s.filter3d.data();
  return v;
}

template <class T>
struct TraceRaySet {
  std::vector<T> origins, directions;
  T t_min = T(0);
  std::size_t count() const { return origins.size() / 3; }
  TraceRaysT<T> view() const { return TraceRaysT<T>{origins.data(), directions.data(), count(), t_min}; }
  void add(const glm::dvec3& o, const glm::dvec3& d) {
    for (int k = 0; k < 3; ++k) {
      origins.push_back(T(o[k]));
      directions.push_back(T(d[k]));
    }
  }
};

struct TraceSceneSpec {
  int count = 6, sh_degree = 3, n_extras = 2;
  double spread = 0.7;                    // positions uniform in [-spread, spread]^3
  double log_scale_lo = std::log(0.15), log_scale_hi = std::log(0.45);
  double anisotropy = 0.0;                // extra log-scale spread per axis (flat / elongated Gaussians)
  double logit_lo = -1.0, logit_hi = 1.5;
  double sh_sigma = 0.25;
  bool emit = false, filter3d = false;
};

template <class T>
SceneArrays<T> random_trace_scene(std::mt19937& rng, const TraceSceneSpec& spec) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), u01(0.0, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  SceneArrays<T> s;
  s.count = spec.count;
  s.sh_degree = spec.sh_degree;
  s.n_extras = spec.n_extras;
  for (int i = 0; i < spec.count; ++i) {
    for (int k = 0; k < 3; ++k) s.positions.push_back(T(spec.spread * u(rng)));
    const double base = spec.log_scale_lo + (spec.log_scale_hi - spec.log_scale_lo) * u01(rng);
    for (int k = 0; k < 3; ++k) s.log_scales.push_back(T(base + spec.anisotropy * u(rng)));
    for (int k = 0; k < 4; ++k) s.rotations.push_back(T(n01(rng) * (0.6 + 0.8 * u01(rng))));
    s.logits.push_back(T(spec.logit_lo + (spec.logit_hi - spec.logit_lo) * u01(rng)));
    for (int k = 0; k < 48; ++k) s.sh.push_back(T(k < 3 ? 0.6 * u(rng) : spec.sh_sigma * n01(rng)));
    for (int e = 0; e < spec.n_extras; ++e) s.extras.push_back(T(u01(rng)));
    if (spec.emit) s.emit.push_back(T(0.2 + 0.8 * u01(rng)));
    if (spec.filter3d) s.filter3d.push_back(T(0.002 + 0.01 * u01(rng)));
  }
  return s;
}

// Rays from points around (and some inside) the scene towards random points near its centre.
template <class T>
TraceRaySet<T> random_rays(std::mt19937& rng, int n, double origin_dist, double target_spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> n01(0.0, 1.0);
  TraceRaySet<T> r;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 o(n01(rng), n01(rng), n01(rng));
    o = glm::normalize(o) * origin_dist * (0.3 + 0.7 * std::abs(u(rng)));
    const glm::dvec3 target(target_spread * u(rng), target_spread * u(rng), target_spread * u(rng));
    glm::dvec3 d = target - o;
    d *= (0.5 + std::abs(u(rng))) / glm::length(d);  // not unit length: t* is in units of |d|
    r.add(o, d);
  }
  return r;
}

// ---- brute-force reference --------------------------------------------------------------------------------
template <class T>
struct RefRay {
  T color[3] = {0, 0, 0}, depth = 0, alpha = 0;
  std::vector<T> extras;
  int hits = 0;
};

template <class T>
std::vector<RefRay<T>> reference_trace(const SceneArrays<T>& s, const TraceRaySet<T>& rays) {
  using V = gmath::Vec3<T>;
  std::vector<trace::TracePrim<T>> prims;
  for (int i = 0; i < s.count; ++i) {
    T lo[3], hi[3];
    prims.push_back(trace::make_prim(&s.positions[3 * i], &s.log_scales[3 * i], &s.rotations[4 * i], s.logits[i],
                                     s.filter3d.empty() ? T(0) : s.filter3d[i], lo, hi));
  }
  std::vector<RefRay<T>> out(rays.count());
  for (std::size_t r = 0; r < rays.count(); ++r) {
    const V o(rays.origins[3 * r], rays.origins[3 * r + 1], rays.origins[3 * r + 2]);
    const V d(rays.directions[3 * r], rays.directions[3 * r + 1], rays.directions[3 * r + 2]);
    std::vector<std::tuple<T, int, T>> hits;  // t, index, alpha
    for (int i = 0; i < s.count; ++i) {
      trace::HitEval<T> h;
      if (trace::eval_hit(prims[i], o, d, rays.t_min, h)) hits.emplace_back(h.t, i, h.alpha);
    }
    std::sort(hits.begin(), hits.end());
    RefRay<T>& res = out[r];
    res.extras.assign(std::size_t(s.n_extras), T(0));
    T trans = 1;
    for (const auto& [t, i, a] : hits) {
      if (trans * (1 - a) < T(1e-4)) break;
      const T w = a * trans;
      const V c = gmath::sh_color<T>(s.sh_degree, &s.sh[48 * std::size_t(i)], d, V(T(0)));
      const T em = s.emit.empty() ? T(1) : s.emit[i];
      for (int k = 0; k < 3; ++k) res.color[k] += w * em * c[k];
      res.depth += w * t;
      for (int e = 0; e < s.n_extras; ++e) res.extras[e] += w * s.extras[std::size_t(s.n_extras) * i + e];
      trans *= 1 - a;
      ++res.hits;
    }
    res.alpha = 1 - trans;
  }
  return out;
}

// ---- the fixture scene (../shared/fixtures/rasterizer_garden + tracer_garden) ----------------------------
struct FixtureScene {
  SceneArrays<float> scene;  // n_extras = 1: the label
  TraceRaySet<float> rays;
  std::vector<double> ref_color, ref_depth, ref_alpha, ref_label, ref_hits;
};

inline FixtureScene load_tracer_fixture(const std::filesystem::path& shared) {
  const auto rg = shared / "fixtures/rasterizer_garden";
  const auto tg = shared / "fixtures/tracer_garden";
  const NpyArray means = load_npy(rg / "means.npy"), scales = load_npy(rg / "scales.npy"),
                 quats = load_npy(rg / "quats_wxyz.npy"), opac = load_npy(rg / "opacities.npy"),
                 sh = load_npy(rg / "sh.npy"), labels = load_npy(tg / "labels.npy");
  FixtureScene f;
  SceneArrays<float>& s = f.scene;
  s.count = int(means.shape[0]);
  s.sh_degree = 3;
  s.n_extras = 1;
  for (int i = 0; i < s.count; ++i) {
    for (int k = 0; k < 3; ++k) s.positions.push_back(float(means.data[3 * i + k]));
    for (int k = 0; k < 3; ++k) s.log_scales.push_back(float(std::log(scales.data[3 * i + k])));
    for (int k = 0; k < 4; ++k) s.rotations.push_back(float(quats.data[4 * i + k]));
    const double o = opac.data[i];
    s.logits.push_back(float(std::log(o / (1 - o))));
    for (int k = 0; k < 48; ++k) s.sh.push_back(float(sh.data[48 * std::size_t(i) + k]));
    s.extras.push_back(float(labels.data[i]));
  }
  const NpyArray ro = load_npy(tg / "rays_o.npy"), rd = load_npy(tg / "rays_d.npy");
  f.rays.origins.assign(ro.data.begin(), ro.data.end());
  f.rays.directions.assign(rd.data.begin(), rd.data.end());
  f.ref_color = load_npy(tg / "ref_color.npy").data;
  f.ref_depth = load_npy(tg / "ref_depth.npy").data;
  f.ref_alpha = load_npy(tg / "ref_alpha.npy").data;
  f.ref_label = load_npy(tg / "ref_label.npy").data;
  f.ref_hits = load_npy(tg / "ref_hits.npy").data;
  return f;
}

}  // namespace goris::test
