#pragma once
// The per-ray part of the Gaussian tracer, shared by every backend: hits are gathered in rounds of the k
// nearest (a sorted, bounded per-ray list, filled by a backend's `collector`), blended front to back, and
// the next round starts after the last hit of the previous one, until the ray is opaque or runs out of hits.
// Hits are ordered by (t*, Gaussian index), so rounds never lose or repeat a hit, ties included.
//
// A collector is a callable  void(const Vec3<T>& o, const Vec3<T>& d, T t_min, RoundStart<T> start,
// HitList<T>& list)  that inserts (with consider_hit) every hit after `start` (list.n = 0 on entry); it may
// stop looking beyond list.t[cap - 1] once the list is full.
#include <cstdint>

#include "render/math/sh.h"
#include "render/trace/trace_hit.h"

namespace goris::trace {

constexpr int kMaxTraceExtras = 16;
constexpr std::uint32_t kNoId = 0xffffffffu;

// What the per-ray code reads; pointers on the backend's device.
template <class T>
struct TraceScene {
  int count = 0;
  const TracePrim<T>* prims = nullptr;  // [N]
  const T* sh = nullptr;                // [N][16][3]
  int sh_degree = 0;
  const T* extras = nullptr;  // [N][n_extras]
  int n_extras = 0;
  const T* emit = nullptr;  // [N] colour weight (null: every Gaussian emits with weight 1)
};

// A round's sorted hits; trans/phi are scratch for the backward pass (may be null in the forward pass).
template <class T>
struct HitList {
  T* t;
  T* alpha;
  std::uint32_t* id;
  T* trans;
  T* phi;
  int cap;
  int n;
};

// Hits of a round come strictly after (t, id) in (t*, index) order; the first round uses id = kNoId.
template <class T>
struct RoundStart {
  T t;
  std::uint32_t id;
};

template <class T>
GORIS_HDI bool hit_before(T ta, std::uint32_t ia, T tb, std::uint32_t ib) {
  return ta < tb || (ta == tb && ia < ib);
}

// Inserts a hit into the sorted list, dropping the farthest when full. Returns true when the list is full
// (the collector may then cull everything beyond list.t[cap - 1]).
template <class T>
GORIS_HDI bool insert_hit(HitList<T>& l, T t, T alpha, std::uint32_t id) {
  if (l.n == l.cap && !hit_before(t, id, l.t[l.n - 1], l.id[l.n - 1])) return true;
  int pos = l.n;
  while (pos > 0 && hit_before(t, id, l.t[pos - 1], l.id[pos - 1])) --pos;
  if (pos > 0 && l.t[pos - 1] == t && l.id[pos - 1] == id) return l.n == l.cap;  // reported twice
  if (l.n == l.cap) --l.n;
  for (int i = l.n; i > pos; --i) {
    l.t[i] = l.t[i - 1];
    l.alpha[i] = l.alpha[i - 1];
    l.id[i] = l.id[i - 1];
  }
  l.t[pos] = t;
  l.alpha[pos] = alpha;
  l.id[pos] = id;
  ++l.n;
  return l.n == l.cap;
}

// Evaluates Gaussian `id` for a collector and inserts it when it is a hit after `start`.
// Returns true when the list is full.
template <class T>
GORIS_HDI bool consider_hit(const TracePrim<T>& pr, std::uint32_t id, const Vec3<T>& o, const Vec3<T>& d, T t_min,
                            RoundStart<T> start, HitList<T>& l) {
  HitEval<T> h;
  if (!eval_hit(pr, o, d, t_min, h)) return l.n == l.cap;
  if (!hit_before(start.t, start.id, h.t, id)) return l.n == l.cap;  // kNoId: strictly after start.t
  return insert_hit(l, h.t, h.alpha, id);
}

// SH basis of the ray direction (one per ray: every hit's colour is evaluated in the same direction).
template <class T>
GORIS_HDI void ray_basis(int degree, const Vec3<T>& d, T* basis, Vec3<T>* basis_grad) {
  sh_basis<T>(degree, glm::normalize(d), basis, basis_grad);
}

// Unclamped SH colour + 0.5 of Gaussian g in the ray direction.
template <class T>
GORIS_HDI Vec3<T> raw_color(const TraceScene<T>& sc, std::uint32_t g, const T* basis) {
  const T* sh = sc.sh + std::size_t(g) * 48;
  Vec3<T> c(T(0.5));
  const int nc = sh_coeff_count(sc.sh_degree);
  for (int k = 0; k < nc; ++k) c += basis[k] * Vec3<T>(sh[3 * k], sh[3 * k + 1], sh[3 * k + 2]);
  return c;
}

template <class T>
GORIS_HDI Vec3<T> clamp_color(const Vec3<T>& c) {
  return Vec3<T>(max(c.x, T(0)), max(c.y, T(0)), max(c.z, T(0)));
}

template <class T>
GORIS_HDI T emit_of(const TraceScene<T>& sc, std::uint32_t g) { return sc.emit ? sc.emit[g] : T(1); }

// Runs the rounds from `start` with transmittance `trans`, calling visit(list index, T_before) for every
// blended hit. Returns the final transmittance; stops before the hit that would bring T below 1e-4.
template <class T, class Collect, class Visit>
GORIS_HDI T blend_rounds(const Vec3<T>& o, const Vec3<T>& d, T t_min, RoundStart<T> start, T trans, HitList<T>& l,
                         Collect& collect, Visit&& visit) {
  for (;;) {
    l.n = 0;
    collect(o, d, t_min, start, l);
    for (int i = 0; i < l.n; ++i) {
      const T next = trans * (T(1) - l.alpha[i]);
      if (next < TraceConst<T>::T_min()) return trans;
      visit(i, trans);
      trans = next;
    }
    if (l.n < l.cap) return trans;
    start = RoundStart<T>{l.t[l.n - 1], l.id[l.n - 1]};
  }
}

// Blended values of one ray.
template <class T>
struct RayResult {
  Vec3<T> color;
  T depth;
  T alpha;
  T extras[kMaxTraceExtras];
  int hits;
};

template <class T, class Collect>
GORIS_HDI void trace_ray(const TraceScene<T>& sc, const Vec3<T>& o, const Vec3<T>& d, T t_min, HitList<T>& l,
                         Collect& collect, RayResult<T>& out) {
  T basis[16];
  ray_basis<T>(sc.sh_degree, d, basis, nullptr);
  out.color = Vec3<T>(T(0));
  out.depth = T(0);
  out.hits = 0;
  for (int e = 0; e < sc.n_extras; ++e) out.extras[e] = T(0);
  const T trans = blend_rounds(o, d, t_min, RoundStart<T>{t_min, kNoId}, T(1), l, collect, [&](int i, T tr) {
    const std::uint32_t g = l.id[i];
    const T w = l.alpha[i] * tr;
    out.color += (w * emit_of(sc, g)) * clamp_color(raw_color(sc, g, basis));
    out.depth += w * l.t[i];
    const T* ex = sc.extras + std::size_t(g) * sc.n_extras;
    for (int e = 0; e < sc.n_extras; ++e) out.extras[e] += w * ex[e];
    ++out.hits;
  });
  out.alpha = T(1) - trans;
}

// ---- backward -------------------------------------------------------------------------------------------
// dL/d(outputs) of one ray (zeros for channels without gradient).
template <class T>
struct RayUpstream {
  Vec3<T> color;
  T depth;
  T alpha;
  T extras[kMaxTraceExtras];
};

// dL/d(outputs) of ray r from the per-ray gradient arrays (null: zero); false when all of it is zero.
template <class T>
GORIS_HDI bool load_upstream(const T* color, const T* depth, const T* alpha, const T* extras, int n_extras,
                             std::size_t r, RayUpstream<T>& up) {
  up.color = color ? Vec3<T>(color[3 * r], color[3 * r + 1], color[3 * r + 2]) : Vec3<T>(T(0));
  up.depth = depth ? depth[r] : T(0);
  up.alpha = alpha ? alpha[r] : T(0);
  bool any = up.color.x != T(0) || up.color.y != T(0) || up.color.z != T(0) || up.depth != T(0) || up.alpha != T(0);
  for (int e = 0; e < n_extras; ++e) {
    up.extras[e] = extras ? extras[std::size_t(n_extras) * r + e] : T(0);
    any = any || up.extras[e] != T(0);
  }
  return any;
}

// Per-Gaussian gradient record (summed over hits, turned into parameter gradients by finalize):
// dL/dM (9, row-major), dL/dmean (3), dL/d effective opacity, dL/d emit weight, dL/dsh [nc][3], dL/dextras.
constexpr int kRecM = 0, kRecMean = 9, kRecOpacity = 12, kRecEmit = 13, kRecSh = 14;
GORIS_HDI int record_stride(int sh_degree, int n_extras) { return kRecSh + 3 * sh_coeff_count(sh_degree) + n_extras; }

// phi = dL/d(channels) . (channel values of hit i): the hit's share of dL/d(its weight).
template <class T>
GORIS_HDI T hit_phi(const TraceScene<T>& sc, const RayUpstream<T>& up, std::uint32_t g, T t, const T* basis) {
  T phi = glm::dot(up.color, emit_of(sc, g) * clamp_color(raw_color(sc, g, basis))) + up.depth * t + up.alpha;
  const T* ex = sc.extras + std::size_t(g) * sc.n_extras;
  for (int e = 0; e < sc.n_extras; ++e) phi += up.extras[e] * ex[e];
  return phi;
}

// Row i of a [n][3] array of ray origins or directions.
template <class T>
GORIS_HDI Vec3<T> ray_at(const T* p, std::size_t i) { return Vec3<T>(p[3 * i], p[3 * i + 1], p[3 * i + 2]); }

// Back-propagates one ray: adds per-Gaussian records through acc.add(index, value) (index = g * stride +
// slot) and returns dL/d(ray origin) and dL/d(ray direction). Re-traces the same rounds as trace_ray; each
// round is walked back to front (3DGS) with R = sum of phi w over the hits after it, so one-round rays are
// exact and later rounds only need the tail sum, computed once by a forward sweep.
template <class T, class Collect, class Acc>
GORIS_HDI void trace_ray_backward(const TraceScene<T>& sc, const Vec3<T>& o, const Vec3<T>& d, T t_min,
                                  const RayUpstream<T>& up, HitList<T>& l, Collect& collect, Acc& acc,
                                  Vec3<T>& dorigin, Vec3<T>& ddir) {
  T basis[16];
  Vec3<T> basis_grad[16];
  ray_basis<T>(sc.sh_degree, d, basis, basis_grad);
  const int nc = sh_coeff_count(sc.sh_degree);
  const std::size_t stride = std::size_t(record_stride(sc.sh_degree, sc.n_extras));
  T sh_dot[16];  // sum over hits of sh_k . dcolour
  for (int k = 0; k < nc; ++k) sh_dot[k] = T(0);
  dorigin = Vec3<T>(T(0));
  ddir = Vec3<T>(T(0));

  RoundStart<T> start{t_min, kNoId};
  T trans = T(1);
  T tail = T(0);  // sum of phi w over the hits after the current round
  bool have_tail = false;
  for (;;) {
    // Pass 1: transmittance and phi of this round's blended hits.
    l.n = 0;
    collect(o, d, t_min, start, l);
    int used = 0;
    bool last = l.n < l.cap;
    T tr = trans, round_sum = T(0);
    for (int i = 0; i < l.n; ++i) {
      const T next = tr * (T(1) - l.alpha[i]);
      if (next < TraceConst<T>::T_min()) {
        last = true;
        break;
      }
      l.trans[i] = tr;
      l.phi[i] = hit_phi(sc, up, l.id[i], l.t[i], basis);
      round_sum += l.phi[i] * l.alpha[i] * tr;
      tr = next;
      ++used;
    }
    const RoundStart<T> next_start{l.n ? l.t[l.n - 1] : T(0), l.n ? l.id[l.n - 1] : kNoId};
    T after = T(0);
    if (!last) {
      if (!have_tail) {  // one forward sweep over the rest of the ray, then re-gather this round
        // (blend_rounds overwrites t/alpha/id only; this round's trans/phi stay.)
        T sum = T(0);
        blend_rounds(o, d, t_min, next_start, tr, l, collect,
                     [&](int i, T ti) { sum += hit_phi(sc, up, l.id[i], l.t[i], basis) * l.alpha[i] * ti; });
        tail = sum;
        have_tail = true;
        l.n = 0;
        collect(o, d, t_min, start, l);  // the same hits as before (deterministic)
      } else {
        tail -= round_sum;
      }
      after = tail;
    }
    // Pass 2: back to front.
    T R = after;
    for (int i = used - 1; i >= 0; --i) {
      const std::uint32_t g = l.id[i];
      const T a = l.alpha[i], Ti = l.trans[i], w = a * Ti;
      const T dalpha = Ti * l.phi[i] - R / (T(1) - a);
      R += l.phi[i] * w;
      HitEval<T> h;
      eval_hit(sc.prims[g], o, d, t_min, h);  // a hit before, so the same values again
      const HitGrad<T> hg = eval_hit_vjp(sc.prims[g], d, h, dalpha, up.depth * w);
      dorigin += hg.dorigin;
      ddir += hg.ddir;
      const std::size_t base = std::size_t(g) * stride;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) acc.add(base + kRecM + 3 * r + c, at(hg.dM, r, c));
      for (int k = 0; k < 3; ++k) acc.add(base + kRecMean + k, hg.dmean[k]);
      acc.add(base + kRecOpacity, hg.dopacity);
      // Colour: c = emit * clamp(raw); a clamped channel passes no gradient.
      const Vec3<T> raw = raw_color(sc, g, basis);
      const T em = emit_of(sc, g);
      acc.add(base + kRecEmit, w * glm::dot(up.color, clamp_color(raw)));
      const Vec3<T> dc((raw.x > T(0) ? up.color.x : T(0)) * w * em, (raw.y > T(0) ? up.color.y : T(0)) * w * em,
                       (raw.z > T(0) ? up.color.z : T(0)) * w * em);
      const T* sh = sc.sh + std::size_t(g) * 48;
      for (int k = 0; k < nc; ++k) {
        acc.add(base + kRecSh + 3 * k + 0, basis[k] * dc.x);
        acc.add(base + kRecSh + 3 * k + 1, basis[k] * dc.y);
        acc.add(base + kRecSh + 3 * k + 2, basis[k] * dc.z);
        sh_dot[k] += sh[3 * k] * dc.x + sh[3 * k + 1] * dc.y + sh[3 * k + 2] * dc.z;
      }
      const std::size_t ebase = base + kRecSh + 3 * nc;
      for (int e = 0; e < sc.n_extras; ++e) acc.add(ebase + e, up.extras[e] * w);
    }
    if (last) break;
    trans = tr;
    start = next_start;
  }
  Vec3<T> dhat(T(0));
  for (int k = 0; k < nc; ++k) dhat += basis_grad[k] * sh_dot[k];
  ddir += normalize_vjp(d, dhat);
}

// Turns Gaussian i's record into parameter gradients (+=; null outputs skipped).
template <class T>
struct ParamGradOut {
  T* positions;
  T* log_scales;
  T* rotations;
  T* opacity_logits;
  T* sh;
  T* extras;
  T* emit;
};

template <class T>
GORIS_HDI void finalize_record(const T* log_scale, const T* quat, T logit, T f3d, const T* rec,
                               int sh_degree, int n_extras, std::size_t i, const ParamGradOut<T>& out) {
  Mat3<T> dM;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) at(dM, r, c) = rec[kRecM + 3 * r + c];
  const ParamGrad<T> pg = prim_params_vjp(log_scale, quat, logit, f3d, dM, rec[kRecOpacity]);
  if (out.positions)
    for (int k = 0; k < 3; ++k) out.positions[3 * i + k] += rec[kRecMean + k];
  if (out.log_scales)
    for (int k = 0; k < 3; ++k) out.log_scales[3 * i + k] += pg.dlog_scale[k];
  if (out.rotations)
    for (int k = 0; k < 4; ++k) out.rotations[4 * i + k] += pg.dquat[k];
  if (out.opacity_logits) out.opacity_logits[i] += pg.dlogit;
  const int nc = sh_coeff_count(sh_degree);
  if (out.sh)
    for (int k = 0; k < 3 * nc; ++k) out.sh[48 * i + k] += rec[kRecSh + k];
  if (out.extras)
    for (int e = 0; e < n_extras; ++e) out.extras[std::size_t(n_extras) * i + e] += rec[kRecSh + 3 * nc + e];
  if (out.emit) out.emit[i] += rec[kRecEmit];
}

}  // namespace goris::trace
