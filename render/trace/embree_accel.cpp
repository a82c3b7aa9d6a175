// Embree 3 user geometry over the Gaussians' boxes; see embree_accel.h.
#include "render/trace/embree_accel.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <embree3/rtcore.h>

#include "core/util/error.h"

namespace goris::trace {

struct EmbreeAccel::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  std::size_t count = 0;
  std::vector<RTCBounds> boxes;
  // Which boxes were empty (lo > hi: a Gaussian that cannot reach 1/255) at the last full build. A refit
  // over another set of empty boxes traces differently in the last bits from a build over them, so a run
  // resumed from a checkpoint (whose first build is a fresh one) would drift from the uninterrupted run:
  // the set changing (an opacity crossing 1/255, the reflection rays' transparency following new emit
  // weights) rebuilds instead.
  std::vector<std::uint8_t> empty;
};

namespace {

// The intersect context carries the ray's round state to the callback (the RTC context comes first, so
// Embree's pointer converts back).
struct RoundContext {
  RTCIntersectContext rtc;
  const TracePrim<float>* prims;
  HitList<float>* list;
  Vec3<float> o, d;
  float t_min;
  RoundStart<float> start;
};

void bounds_callback(const RTCBoundsFunctionArguments* args) {
  const auto* impl = static_cast<const EmbreeAccel::Impl*>(args->geometryUserPtr);
  *args->bounds_o = impl->boxes[args->primID];
}

void intersect_callback(const RTCIntersectFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<RoundContext*>(args->context);
  for (unsigned lane = 0; lane < args->N; ++lane) {  // rtcIntersect1: N = 1
    if (!args->valid[lane]) continue;
    HitList<float>& l = *ctx->list;
    const bool full = consider_hit(ctx->prims[args->primID], args->primID, ctx->o, ctx->d, ctx->t_min, ctx->start, l);
    if (full) {
      RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
      float& tfar = RTCRayN_tfar(ray, args->N, lane);
      // Boxes entered beyond the farthest kept hit cannot hold a nearer one; the margin keeps equal-t hits.
      tfar = std::min(tfar, std::nextafter(l.t[l.n - 1], std::numeric_limits<float>::infinity()));
    }
  }
}

void occluded_callback(const RTCOccludedFunctionNArguments*) {}  // rtcOccluded is never called

void check(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw Error("tracer (Embree)", std::string(what) + " failed with Embree error " + std::to_string(int(e)));
}

}  // namespace

EmbreeAccel::EmbreeAccel() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("tracer (Embree)", "rtcNewDevice failed");
}

EmbreeAccel::~EmbreeAccel() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->geometry) rtcReleaseGeometry(impl_->geometry);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

bool EmbreeAccel::build(const float* lo, const float* hi, std::size_t n, bool allow_refit) {
  Impl& m = *impl_;
  if (n > std::size_t(std::numeric_limits<unsigned>::max() - 1))
    throw Error("tracer (Embree)", std::to_string(n) + " Gaussians exceed Embree's primitive count");
  bool refit = allow_refit && m.scene && n == m.count;
  m.boxes.resize(n);
  m.empty.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    RTCBounds& b = m.boxes[i];
    b.lower_x = lo[3 * i];
    b.lower_y = lo[3 * i + 1];
    b.lower_z = lo[3 * i + 2];
    b.upper_x = hi[3 * i];
    b.upper_y = hi[3 * i + 1];
    b.upper_z = hi[3 * i + 2];
    b.align0 = b.align1 = 0.0f;
    const std::uint8_t empty = b.lower_x > b.upper_x ? 1 : 0;
    if (refit && empty != m.empty[i]) refit = false;
    m.empty[i] = empty;
  }
  if (refit) {
    // Two-level scene (quality LOW) so that the geometry's REFIT quality is honoured.
    rtcSetGeometryBuildQuality(m.geometry, RTC_BUILD_QUALITY_REFIT);
    rtcCommitGeometry(m.geometry);
    rtcCommitScene(m.scene);
    check(m.device, "BVH refit");
    return true;
  }
  if (m.scene) rtcReleaseScene(m.scene);
  if (m.geometry) rtcReleaseGeometry(m.geometry);
  m.scene = rtcNewScene(m.device);
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_DYNAMIC);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_LOW);
  m.geometry = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryBuildQuality(m.geometry, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetGeometryUserPrimitiveCount(m.geometry, unsigned(n));
  rtcSetGeometryUserData(m.geometry, &m);
  rtcSetGeometryBoundsFunction(m.geometry, bounds_callback, &m);
  rtcSetGeometryIntersectFunction(m.geometry, intersect_callback);
  rtcSetGeometryOccludedFunction(m.geometry, occluded_callback);
  rtcCommitGeometry(m.geometry);
  rtcAttachGeometry(m.scene, m.geometry);
  rtcCommitScene(m.scene);
  check(m.device, "BVH build");
  m.count = n;
  return false;
}

void EmbreeAccel::Collector::operator()(const Vec3<float>& o, const Vec3<float>& d, float t_min,
                                        RoundStart<float> start, HitList<float>& l) const {
  const Impl& m = *accel->impl_;
  if (m.count == 0) return;
  RoundContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.prims = prims;
  ctx.list = &l;
  ctx.o = o;
  ctx.d = d;
  ctx.t_min = t_min;
  ctx.start = start;
  RTCRayHit rh;
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = start.t;  // every hit of this round has t* >= start.t
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m.scene, &ctx.rtc, &rh);
}

}  // namespace goris::trace
