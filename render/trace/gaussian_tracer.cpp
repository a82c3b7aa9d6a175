// GaussianTracer: validation and dispatch to the CPU drivers (Embree or LBVH collectors) or the CUDA backend.
#include "render/trace/gaussian_tracer.h"

#include <cmath>
#include <string>

#include "core/compute/cuda_dispatch.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/trace/embree_accel.h"
#include "render/trace/trace_build.h"
#include "render/trace/trace_cpu.h"
#include "render/trace/trace_cuda.h"

namespace goris {

using namespace goris::trace;

namespace {

const char* const kWho = "tracer";

void validate_view(const GaussianView& v) {
  if (v.count < 0) throw Error(kWho, "negative Gaussian count");
  if (v.sh_degree < 0 || v.sh_degree > 3)
    throw Error(kWho, "SH degree " + std::to_string(v.sh_degree) + " is outside 0..3");
  if (v.n_extras < 0 || v.n_extras > kMaxTraceExtras)
    throw Error(kWho, std::to_string(v.n_extras) + " extra channels (at most " + std::to_string(kMaxTraceExtras) + ")");
  if (v.count > 0 && (!v.positions || !v.log_scales || !v.rotations || !v.opacity_logits || !v.sh))
    throw Error(kWho, "Gaussian view has null parameter arrays");
  if (v.count > 0 && v.n_extras > 0 && !v.extras) throw Error(kWho, "Gaussian view declares extras but has none");
}

bool finite(const float* p, int n) {
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(p[k])) return false;
  return true;
}

// Host-side check of the parameters (CPU builds only: device memory is not inspected).
void check_finite_cpu(const GaussianView& v, const float* emit) {
  for (int i = 0; i < v.count; ++i) {
    const float* q = v.rotations + 4 * std::size_t(i);
    const bool ok = finite(v.positions + 3 * std::size_t(i), 3) && finite(v.log_scales + 3 * std::size_t(i), 3) &&
                    finite(q, 4) && std::isfinite(v.opacity_logits[i]) &&
                    (q[0] != 0.0f || q[1] != 0.0f || q[2] != 0.0f || q[3] != 0.0f) &&
                    (!v.filter3d_var || (std::isfinite(v.filter3d_var[i]) && v.filter3d_var[i] >= 0.0f)) &&
                    (!emit || std::isfinite(emit[i]));
    if (!ok)
      throw Error(kWho, "Gaussian " + std::to_string(i) +
                            " has a non-finite parameter, a zero quaternion or a negative 3D filter variance");
  }
}

void validate_rays(const TraceRays& r, Device d) {
  if (r.count == 0) return;
  if (!r.origins || !r.directions) throw Error(kWho, "rays have null origin or direction arrays");
  if (!(r.t_min >= 0.0f) || !std::isfinite(r.t_min)) throw Error(kWho, "t_min must be finite and >= 0");
  if (d != Device::CPU) return;
  for (std::size_t i = 0; i < r.count; ++i) {
    const float* o = r.origins + 3 * i;
    const float* dir = r.directions + 3 * i;
    if (!finite(o, 3) || !finite(dir, 3) || (dir[0] == 0.0f && dir[1] == 0.0f && dir[2] == 0.0f))
      throw Error(kWho, "ray " + std::to_string(i) + " has a non-finite origin or direction, or a zero direction");
  }
}

}  // namespace

struct GaussianTracer::Impl {
  Device device;
  TraceSettings settings;
  bool built = false;
  bool refitted = false;
  GaussianView view;
  const float* emit = nullptr;
  PrimData prims;
  LbvhData lbvh;
  std::unique_ptr<EmbreeAccel> embree;

  TraceScene<float> scene() const {
    TraceScene<float> sc;
    sc.count = view.count;
    sc.prims = prims.prims.data();
    sc.sh = view.sh;
    sc.sh_degree = view.sh_degree;
    sc.extras = view.extras;
    sc.n_extras = view.n_extras;
    sc.emit = emit;
    return sc;
  }
  void require_built() const {
    if (!built) throw Error(kWho, "trace/backward called before build()");
  }
};

GaussianTracer::GaussianTracer(Device device, const TraceSettings& settings) : impl_(std::make_unique<Impl>()) {
  if (settings.hits_per_round < 1) throw Error(kWho, "hits_per_round must be at least 1");
  if (device == Device::CUDA && !cuda_compiled()) throw Error(kWho, "CUDA device requested but this build has no CUDA backend");
  impl_->device = device;
  impl_->settings = settings;
}

GaussianTracer::~GaussianTracer() = default;
GaussianTracer::GaussianTracer(GaussianTracer&&) noexcept = default;
GaussianTracer& GaussianTracer::operator=(GaussianTracer&&) noexcept = default;

Device GaussianTracer::device() const { return impl_->device; }
const TraceSettings& GaussianTracer::settings() const { return impl_->settings; }
int GaussianTracer::count() const { return impl_->view.count; }
bool GaussianTracer::last_build_refitted() const { return impl_->refitted; }

void GaussianTracer::build(const GaussianView& gaussians, const float* emit) {
  Impl& m = *impl_;
  validate_view(gaussians);
  const bool same_count = m.built && gaussians.count == m.view.count;
  m.built = false;
  m.view = gaussians;
  m.emit = emit;
  m.refitted = false;
  const GaussiansT<float> g = to_raster_view(gaussians);
  if (m.device == Device::CUDA) {
    GORIS_CUDA_CALL(kWho, build_cuda(g, m.prims, m.lbvh));  // the LBVH is rebuilt each time: it is cheap on the GPU
  } else {
    check_finite_cpu(gaussians, emit);
    build_prims<Device::CPU>(g, m.prims);
    if (m.settings.cpu_accel == TraceAccel::Embree) {
      if (!m.embree) m.embree = std::make_unique<EmbreeAccel>();
      m.refitted = m.embree->build(m.prims.lo.data(), m.prims.hi.data(), m.prims.prims.size(), m.settings.refit && same_count);
    } else {
      build_lbvh<Device::CPU>(m.prims, m.lbvh);
    }
  }
  m.built = true;
}

void GaussianTracer::trace(const TraceRays& rays, const TraceOutputs& out) const {
  const Impl& m = *impl_;
  m.require_built();
  validate_rays(rays, m.device);
  if (rays.count == 0) return;
  const TraceScene<float> sc = m.scene();
  if (m.device == Device::CUDA) {
    GORIS_CUDA_CALL(kWho, forward_cuda(sc, m.lbvh.view(), rays, out));
  } else if (m.settings.cpu_accel == TraceAccel::Embree) {
    forward_cpu(sc, rays, m.settings.hits_per_round, out, [&] { return m.embree->collector(sc.prims); });
  } else {
    forward_cpu(sc, rays, m.settings.hits_per_round, out, [&] { return LbvhCollector{m.lbvh.view(), sc.prims}; });
  }
}

void GaussianTracer::backward(const TraceRays& rays, const TraceOutputGrads& grad_out, const GaussianGradView& grads,
                              const TraceRayGrads& ray_grads, float* grad_emit) const {
  const Impl& m = *impl_;
  m.require_built();
  validate_rays(rays, m.device);
  if (rays.count == 0) return;
  const TraceScene<float> sc = m.scene();
  const GaussiansT<float> g = to_raster_view(m.view);
  const GaussianGradsT<float> gg = to_raster_grads(grads);
  if (m.device == Device::CUDA) {
    GORIS_CUDA_CALL(kWho, backward_cuda(sc, m.lbvh.view(), g, rays, grad_out, gg, ray_grads, grad_emit,
                                        m.settings.max_grad_scratch_bytes));
  } else if (m.settings.cpu_accel == TraceAccel::Embree) {
    backward_cpu(sc, g, rays, m.settings.hits_per_round, grad_out, gg, ray_grads, grad_emit,
                 m.settings.max_grad_scratch_bytes, [&] { return m.embree->collector(sc.prims); });
  } else {
    backward_cpu(sc, g, rays, m.settings.hits_per_round, grad_out, gg, ray_grads, grad_emit,
                 m.settings.max_grad_scratch_bytes, [&] { return LbvhCollector{m.lbvh.view(), sc.prims}; });
  }
}

}  // namespace goris
