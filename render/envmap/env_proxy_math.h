#pragma once
// A distance-aware ("parallax-corrected") environment lookup for bounded scenes, shared by the CPU and CUDA
// drivers and templated on the scalar type.
//
// The paper's environment lies at infinity: the radiance a surface point x receives from direction w is
// E(w), whatever x is. A light near the scene (the data sets' area light, a window of a room) then sits in
// a different direction from every point of the glossy surface, and one cube map cannot place its
// reflection consistently across views: the loss settles on a blur (docs/design/deviations.md, The
// environment on a sphere). Here the environment lies on a sphere of radius R around a centre c instead: the
// ray x + t w meets the sphere at q = x + t w (t > 0), and the map is read in the direction of q from c. A
// light on the sphere is then seen at one texel from every surface point. As R grows the lookup tends to the
// paper's (w). Points outside the sphere (none in a scene the cameras surround, c and R chosen by the
// trainer) read E(w).
#include <cmath>

#include <glm/glm.hpp>

#include "core/compute/hd.h"
#include "render/envmap/cube_map_math.h"  // Vec3

namespace goris::envmap {

// Where ray (x, w) meets the sphere: o = x - c, t = -(o.w) + s, s = sqrt((o.w)^2 - |o|^2 + R^2).
template <class T>
struct ProxyHit {
  Vec3<T> o;    // x - c
  Vec3<T> dir;  // (o + t w) / R: unit; = w when there is no hit
  T t = 0, s = 0;
  bool hit = false;  // x inside the sphere (|o| < R): the ray leaves it at t > 0
};

template <class T>
GORIS_HDI ProxyHit<T> proxy_hit(const Vec3<T>& x, const Vec3<T>& w, const Vec3<T>& centre, T radius) {
  ProxyHit<T> h;
  h.o = x - centre;
  h.dir = w;
  if (!(radius > T(0))) return h;
  const T b = glm::dot(h.o, w);
  const T c = glm::dot(h.o, h.o) - radius * radius;
  if (!(c < T(0))) return h;  // on or outside the sphere: the lookup at infinity
  h.s = std::sqrt(b * b - c);
  h.t = h.s - b;
  h.dir = (h.o + h.t * w) / radius;
  h.hit = true;
  return h;
}

// VJP of proxy_hit's direction: g = dL/d(dir) -> dL/dw and dL/dx (+= into both).
// dt/dw = o (b / s - 1), dt/do = (b w - o) / s - w; dir = (o + t w) / R.
template <class T>
GORIS_HDI void proxy_hit_vjp(const ProxyHit<T>& h, const Vec3<T>& w, T radius, const Vec3<T>& g,
                             Vec3<T>* dw, Vec3<T>* dx) {
  if (!h.hit) {
    *dw += g;
    return;
  }
  const T b = glm::dot(h.o, w);
  const T gw = glm::dot(g, w) / radius;
  const Vec3<T> dt_dw = h.o * (b / h.s - T(1));
  const Vec3<T> dt_do = (b * w - h.o) / h.s - w;
  *dw += (h.t / radius) * g + gw * dt_dw;
  *dx += g / radius + gw * dt_do;
}

}  // namespace goris::envmap
