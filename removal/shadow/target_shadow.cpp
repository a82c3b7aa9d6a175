#include "removal/shadow/target_shadow.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/scene/cap_directions.h"
#include "core/util/error.h"

namespace goris {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct LineFit {
  double b = 0.0, beta = 0.0, r2 = 0.0;
};

// Weighted least squares y = b + beta x.
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w) {
  double sw = 0, sx = 0, sy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sw += w[i], sx += w[i] * x[i], sy += w[i] * y[i];
  LineFit f;
  if (sw <= 0) return f;
  const double mx = sx / sw, my = sy / sw;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mx, dy = y[i] - my;
    sxx += w[i] * dx * dx, sxy += w[i] * dx * dy, syy += w[i] * dy * dy;
  }
  f.beta = sxx > 1e-12 ? sxy / sxx : 0.0;
  f.b = my - f.beta * mx;
  f.r2 = (sxx > 1e-12 && syy > 1e-12) ? sxy * sxy / (sxx * syy) : 0.0;
  return f;
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A display colour (negatives clamped) in linear radiance: shadows scale radiance.
glm::dvec3 to_linear(const glm::vec3& display, double gamma) {
  const glm::dvec3 c = glm::max(glm::dvec3(display), glm::dvec3(0.0));
  return {std::pow(c.x, gamma), std::pow(c.y, gamma), std::pow(c.z, gamma)};
}

// How clearly the shadowed samples (s > 0.5) are darker than the unshadowed ones (s < 0.05): the difference of
// their mean y over its standard error (samples of weight 0 left out; 0 when either side has under 2).
double shadow_contrast(const std::vector<double>& s, const std::vector<double>& y, const std::vector<double>& w) {
  double n_in = 0, n_out = 0, s_in = 0, s_out = 0, q_in = 0, q_out = 0;
  for (std::size_t q = 0; q < s.size(); ++q) {
    if (!(w[q] > 0)) continue;
    if (s[q] > 0.5) n_in += 1, s_in += y[q], q_in += y[q] * y[q];
    else if (s[q] < 0.05) n_out += 1, s_out += y[q], q_out += y[q] * y[q];
  }
  if (n_in < 2 || n_out < 2) return 0.0;
  const double m_in = s_in / n_in, m_out = s_out / n_out;
  const double v_in = std::max(0.0, q_in / n_in - m_in * m_in), v_out = std::max(0.0, q_out / n_out - m_out * m_out);
  const double se = std::sqrt(v_in / n_in + v_out / n_out);
  return se > 1e-12 ? (m_out - m_in) / se : 0.0;
}

}  // namespace

ShadowGeometry shadow_geometry(const std::vector<glm::vec3>& centres, const std::vector<float>& weights,
                               const SelectionMask& target, const SelectionMask& candidates, const ShadowSettings& st,
                               const MirrorPlane* fallback) {
  const std::size_t n = centres.size();
  if (weights.size() != n || target.size() != n || candidates.size() != n)
    throw Error("target shadow", "per-Gaussian arrays differ in size (" + std::to_string(n) + " centres)");
  if (count_selected(target) == 0) throw Error("target shadow", "the target is empty");
  ShadowGeometry g;
  std::vector<glm::dvec3> tc;  // the target's centres
  for (std::size_t i = 0; i < n; ++i)
    if (target[i]) tc.push_back(glm::dvec3(centres[i])), g.centroid += tc.back();
  g.centroid /= double(tc.size());
  // 90th percentile: a few stray centres must not inflate the neighbourhood.
  std::vector<double> dist;
  for (const glm::dvec3& c : tc) dist.push_back(glm::length(c - g.centroid));
  const std::size_t q = dist.size() * 9 / 10;
  std::nth_element(dist.begin(), dist.begin() + std::ptrdiff_t(q), dist.end());
  g.radius = std::max(dist[q], 1e-6);
  g.reach = st.radius_ratio * g.radius;

  std::vector<glm::vec3> near;
  for (std::size_t i = 0; i < n; ++i)
    if (!target[i] && candidates[i] && weights[i] >= 0.05f && g.in_reach(glm::dvec3(centres[i])))
      near.push_back(centres[i]);
  if (near.size() >= st.min_samples) {
    // The target rests on (or hangs just above) its support: a plane counts only where the target's lowest
    // centres (5th percentile of their heights above it) are within its radius of it. Without this, over a
    // mirror the learned mirror world below the surface wins (the default scene's radiance run: a plane 0.65
    // below the table top).
    std::vector<double> h(tc.size());
    MirrorSettings ps;
    ps.tolerance_ratio = st.plane_tolerance_ratio;
    ps.min_inlier_fraction = st.min_plane_fraction;
    ps.min_glossy = st.min_samples;
    ps.ransac_iterations = 512;
    ps.accept = [&](const glm::dvec3& normal, double offset) {
      const double side = glm::dot(normal, g.centroid) - offset < 0 ? -1.0 : 1.0;
      for (std::size_t k = 0; k < tc.size(); ++k) h[k] = side * (glm::dot(normal, tc[k]) - offset);
      const std::size_t q5 = h.size() / 20;
      std::nth_element(h.begin(), h.begin() + std::ptrdiff_t(q5), h.end());
      return std::abs(h[q5]) <= g.radius;
    };
    g.plane = fit_mirror_plane(near, ps);
  }
  if (!g.plane.found && fallback && fallback->found && std::abs(fallback->signed_distance(g.centroid)) <= g.reach)
    g.plane = *fallback;
  if (!g.plane.found) {
    g.reason = near.size() < st.min_samples
                   ? "only " + std::to_string(near.size()) + " Gaussians near the target: no surface to shade"
                   : "no support plane under the target (" + std::to_string(near.size()) + " Gaussians near it)";
    return g;
  }
  g.up = g.plane.signed_distance(g.centroid) < 0 ? -g.plane.normal : g.plane.normal;
  g.found = true;
  return g;
}

namespace {

// The target's opacity along each point's rays toward each direction of `dirs`, averaged.
std::vector<double> mean_occlusion(const std::vector<glm::vec3>& points, const std::vector<glm::dvec3>& dirs,
                                   const TargetOcclusion& occlusion) {
  const std::size_t m = points.size();
  std::vector<double> s(m, 0.0);
  if (m == 0) return s;
  std::vector<glm::vec3> ray_d(m);
  std::vector<float> alpha(m);
  for (const glm::dvec3& d : dirs) {  // one direction per call keeps the ray arrays small
    std::fill(ray_d.begin(), ray_d.end(), glm::vec3(d));
    std::fill(alpha.begin(), alpha.end(), 0.0f);
    occlusion(points, ray_d, alpha);
    for (std::size_t k = 0; k < m; ++k) s[k] += std::clamp(double(alpha[k]), 0.0, 1.0) / double(dirs.size());
  }
  return s;
}

std::vector<glm::dvec3> cone_of(const glm::dvec3& d, double cone_degrees, const ShadowSettings& st) {
  return cap_directions(d, cone_degrees * kPi / 180.0, cone_degrees > 0 ? st.cone_samples : 1);
}

}  // namespace

TargetShadow fit_target_shadow(const ShadowGeometry& geo, const ShadowSamples& samples, const TargetOcclusion& occlusion,
                               const ShadowSettings& st, const glm::dvec3* known_light) {
  const std::size_t m = samples.size();
  if (samples.colour.size() != m || samples.weight.size() != m)
    throw Error("target shadow", "the samples' arrays differ in size (" + std::to_string(m) + " positions)");
  TargetShadow out;
  out.samples = m;
  if (!geo.found) {
    out.reason = geo.reason;
    return out;
  }
  if (m < st.min_samples) {
    out.reason = "only " + std::to_string(m) + " samples of the support surface near the target";
    return out;
  }
  std::vector<glm::dvec3> lin(m);
  std::vector<double> y(m), w(m);
  for (std::size_t k = 0; k < m; ++k) {
    lin[k] = to_linear(samples.colour[k], st.gamma);
    y[k] = luminance(lin[k]);
    w[k] = std::max(0.0f, samples.weight[k]);
  }
  // Points right under the target are hidden from the views: what they show says nothing about the light.
  const std::vector<double> under = mean_occlusion(samples.position, {geo.up}, occlusion);
  double w_total = 0;
  for (std::size_t k = 0; k < m; ++k) {
    if (under[k] > 0.5) w[k] = 0.0;
    w_total += w[k];
  }
  if (w_total <= 0) {
    out.reason = "every sample lies under the target";
    return out;
  }

  struct Scored {
    glm::dvec3 dir{0, 0, 1};
    double cone = 0.0;
    LineFit fit;
    std::vector<double> s;
    bool valid = false;
  };
  auto score = [&](const glm::dvec3& d, double cone) {
    Scored sc;
    sc.dir = d;
    sc.cone = cone;
    sc.s = mean_occlusion(samples.position, cone_of(d, cone, st), occlusion);
    double shadowed = 0;
    for (std::size_t k = 0; k < m; ++k) shadowed += sc.s[k] > 0.5 ? w[k] : 0.0;
    sc.fit = fit_line(sc.s, y, w);
    sc.valid = shadowed >= st.min_shadowed * w_total && sc.fit.beta < 0;
    return sc;
  };
  auto better = [](const Scored& a, const Scored& b) { return a.valid && (!b.valid || a.fit.r2 > b.fit.r2); };

  // The light's size around a direction: the cones of step 3, kept where they fit better.
  auto widen = [&](Scored best, const std::function<bool(const Scored&, const Scored&)>& better_fit) {
    const glm::dvec3 dir = best.dir;
    for (double cone : st.cone_degrees) {
      if (cone <= 0.0) continue;
      Scored sc = score(dir, cone);
      if (better_fit(sc, best)) best = std::move(sc);
    }
    return best;
  };
  // Strength per channel: y_c = b_c - b_c k_c s.
  // near_light: the known light of step 5 (null for steps 2-4).
  auto result = [&](const Scored& best, const glm::dvec3* near_light) {
    TargetShadow r;
    r.samples = m;
    glm::dvec3 k(0.0);
    for (int c = 0; c < 3; ++c) {
      std::vector<double> yc(m);
      for (std::size_t q = 0; q < m; ++q) yc[q] = lin[q][c];
      const LineFit f = fit_line(best.s, yc, w);
      k[c] = f.b > 1e-9 ? std::clamp(-f.beta / f.b, 0.0, st.max_strength) : 0.0;
    }
    const double k_lum = best.fit.b > 1e-9 ? std::clamp(-best.fit.beta / best.fit.b, 0.0, st.max_strength) : 0.0;
    const double z = shadow_contrast(best.s, y, w);
    r.light_direction = best.dir;
    r.cone_degrees = best.cone;
    r.strength = k;
    r.strength_luminance = k_lum;
    r.r2 = best.fit.r2;
    r.from_known_light = near_light != nullptr;
    r.contrast = z;
    char near[64] = "";
    if (near_light)
      std::snprintf(near, sizeof near, " near the environment's (%.0f deg from it)",
                    std::acos(std::clamp(glm::dot(best.dir, *near_light), -1.0, 1.0)) * 180.0 / kPi);
    char line[240];
    std::snprintf(line, sizeof line, "light (%.2f, %.2f, %.2f)%s, cone %.1f deg, strength %.2f, R^2 %.2f, contrast %.1f",
                  best.dir.x, best.dir.y, best.dir.z, near, best.cone, k_lum, best.fit.r2, z);
    r.found = best.fit.beta < 0 && k_lum >= st.min_strength &&
              (near_light ? z >= st.known_light_min_contrast : best.fit.r2 >= st.min_r2);
    r.reason = r.found ? std::string(line) : std::string("too weak to be a shadow: ") + line;
    return r;
  };

  // The light's direction: the hemisphere on the target's side, then a cap around the best.
  Scored best;
  for (const glm::dvec3& d : cap_directions(geo.up, 0.5 * kPi, st.directions / 2)) {
    Scored sc = score(d, 0.0);
    if (better(sc, best)) best = std::move(sc);
  }
  if (best.valid) {
    const double spacing = std::sqrt(4.0 * kPi / st.directions);
    for (const glm::dvec3& d : cap_directions(best.dir, 2.0 * spacing, st.refine_directions)) {
      Scored sc = score(d, 0.0);
      if (better(sc, best)) best = std::move(sc);
    }
    out = result(widen(std::move(best), better), nullptr);
    if (out.found || !known_light) return out;
  } else {
    out.reason = "no light direction puts enough of the support surface in the target's shadow";
    if (!known_light) return out;
  }

  // Step 5: near the known light, by R^2 alone (its shadow may lie mostly under the target: no share of the
  // samples is asked for), accepted on its strength and contrast.
  auto darker_fit = [](const Scored& a, const Scored& b) { return a.fit.beta < 0 && a.fit.r2 > b.fit.r2; };
  const glm::dvec3 known = glm::normalize(*known_light);
  Scored near = score(known, 0.0);
  for (const glm::dvec3& d :
       cap_directions(known, st.known_light_cap_degrees * kPi / 180.0, st.known_light_directions)) {
    Scored sc = score(d, 0.0);
    if (darker_fit(sc, near)) near = std::move(sc);
  }
  const TargetShadow from_known = result(widen(std::move(near), darker_fit), &known);
  if (from_known.found) return from_known;
  out.reason += "; near the environment's light: " + from_known.reason;
  return out;
}

OthersShadow others_shadow(const TargetShadow& shadow, const ShadowSamples& samples, const TargetOcclusion& target,
                           const TargetOcclusion& others, const ShadowSettings& st) {
  const std::size_t m = samples.size();
  if (samples.colour.size() != m || samples.weight.size() != m)
    throw Error("target shadow", "the samples' arrays differ in size (" + std::to_string(m) + " positions)");
  OthersShadow r;
  if (!shadow.found || m == 0) return r;
  const std::vector<glm::dvec3> cone = cone_of(shadow.light_direction, shadow.cone_degrees, st);
  const std::vector<double> s = mean_occlusion(samples.position, cone, target);
  const std::vector<double> o = mean_occlusion(samples.position, cone, others);
  std::vector<double> y(m), w(m);
  double total = 0, shaded = 0;
  for (std::size_t k = 0; k < m; ++k) {
    y[k] = luminance(to_linear(samples.colour[k], st.gamma));
    w[k] = s[k] < 0.05 ? std::max(0.0f, samples.weight[k]) : 0.0;
    total += w[k];
    shaded += o[k] > 0.5 ? w[k] : 0.0;
  }
  if (total <= 0) return r;
  r.shaded_share = shaded / total;
  const LineFit f = fit_line(o, y, w);
  r.strength = f.b > 1e-9 ? -f.beta / f.b : 0.0;
  r.contradicts = r.shaded_share >= st.min_shadowed && r.strength < st.min_strength;
  return r;
}

std::vector<float> shadow_fraction(const TargetShadow& shadow, const std::vector<glm::vec3>& points,
                                   const TargetOcclusion& occlusion, const ShadowSettings& st) {
  if (!shadow.found) return std::vector<float>(points.size(), 0.0f);
  const std::vector<double> s = mean_occlusion(points, cone_of(shadow.light_direction, shadow.cone_degrees, st), occlusion);
  return std::vector<float>(s.begin(), s.end());
}

glm::vec3 shadow_gain(const TargetShadow& shadow, float s, const ShadowSettings& st) {
  glm::vec3 g(1.0f);
  if (!shadow.found || s <= 0.0f) return g;
  for (int c = 0; c < 3; ++c)
    g[c] = float(std::pow(1.0 / (1.0 - shadow.strength[c] * std::min(1.0f, s)), 1.0 / st.gamma));
  return g;
}

float shadow_fraction_beside_others(float target_share, float others_share, double strength) {
  const double st = std::clamp(double(target_share), 0.0, 1.0), so = std::clamp(double(others_share), 0.0, 1.0);
  const double k = std::clamp(strength, 0.0, 1.0);
  if (so >= 1.0) return 0.0f;
  return float(st * (1.0 - so) / (1.0 - k * so));
}

}  // namespace goris
