// `goris bench raster`: median forward and backward times of the G-buffer rasterizer on a synthetic,
// surface-like scene (Gaussians on a sphere and a ground plane, as a trained scene has them), per stage,
// with the rasterizer's memory, on the CPU and (when present) CUDA, and the CPU/CUDA ratio.
#include <tbb/global_control.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "app/bench/bench_child.h"
#include "app/cli_common/command.h"
#include "core/compute/memory.h"
#include "core/compute/bench.h"
#include "core/util/error.h"
#include "core/util/median.h"
#include "render/raster/rasterizer.h"

namespace {

using goris::Buffer;
using goris::Device;

struct HostScene {
  int n = 0, extras = 0;
  std::vector<float> pos, log_scale, rot, logit, sh, ext;
};

HostScene make_scene(int n, int n_extras, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> g(0.f, 1.f);
  HostScene s;
  s.n = n;
  s.extras = n_extras;
  for (int i = 0; i < n; ++i) {
    float x, y, z;
    if (u(rng) < 0.7f) {  // unit sphere
      x = g(rng), y = g(rng), z = g(rng);
      const float l = std::sqrt(x * x + y * y + z * z) + 1e-9f;
      x /= l, y /= l, z /= l;
    } else {  // ground plane y = 1 (below the sphere in OpenCV's y-down world)
      x = 4.f * u(rng) - 2.f, y = 1.f, z = 4.f * u(rng) - 2.f;
    }
    s.pos.insert(s.pos.end(), {x, y, z});
    for (int k = 0; k < 3; ++k) s.log_scale.push_back(std::log(0.01f + 0.03f * u(rng)));
    s.rot.insert(s.rot.end(), {g(rng), g(rng), g(rng), g(rng)});
    s.logit.push_back(-1.f + 4.f * u(rng));
    for (int k = 0; k < 48; ++k) s.sh.push_back(k < 3 ? 0.5f * g(rng) : 0.05f * g(rng));
    for (int e = 0; e < n_extras; ++e) s.ext.push_back(u(rng));
  }
  if (s.ext.empty()) s.ext.push_back(0.f);
  return s;
}

goris::Camera make_camera(int res) {
  goris::Camera c;
  c.width = c.height = res;
  c.fx = c.fy = 1.1f * float(res);  // about 49 degrees
  c.cx = c.cy = 0.5f * float(res);
  // Looking along +z at the origin from 3.2 units away, slightly from above.
  const float a = 0.3f;
  c.R = glm::mat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a));
  c.t = glm::vec3(0, 0, 3.2f);
  return c;
}

// CPU time of the whole process in ms: on a machine shared with other work, the honest measure of the work
// done (with --threads 1 it is the single-thread time, unaffected by waiting for a core).
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

struct Result {
  double fwd = -1, bwd = -1, fwd_cpu = 0, bwd_cpu = 0, pre = 0, bin = 0, blend = 0, bblend = 0, bgauss = 0, mib = 0;
  std::size_t instances = 0;
};

Result run(Device dev, const HostScene& hs, int res, int iters) {
  Buffer<float> pos(hs.pos, dev), ls(hs.log_scale, dev), rot(hs.rot, dev), lg(hs.logit, dev), sh(hs.sh, dev),
      ext(hs.ext, dev);
  goris::GaussianView v;
  v.count = hs.n;
  v.positions = pos.data(), v.log_scales = ls.data(), v.rotations = rot.data(), v.opacity_logits = lg.data();
  v.sh = sh.data(), v.sh_degree = 3, v.extras = ext.data(), v.n_extras = hs.extras;
  const goris::Camera cam = make_camera(res);
  goris::RasterSettings rs = goris::RasterSettings::mip_splatting();
  rs.profile = true;
  // dL/d(every channel): random, so the whole backward runs.
  const std::size_t P = std::size_t(res) * res;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1e-3f, 1e-3f);
  auto rnd = [&](std::size_t n) {
    std::vector<float> x(n);
    for (auto& e : x) e = u(rng);
    return Buffer<float>(x, dev);
  };
  Buffer<float> gc = rnd(3 * P), ga = rnd(P), gd = rnd(P), gm = rnd(P), gn = rnd(3 * P),
                ge = rnd(std::max<std::size_t>(1, hs.extras * P));
  const goris::GBufferGrad go{gc.data(), ga.data(), gd.data(), gm.data(), gn.data(), hs.extras ? ge.data() : nullptr};
  Buffer<float> d_pos(3 * hs.n, dev), d_ls(3 * hs.n, dev), d_rot(4 * hs.n, dev), d_lg(hs.n, dev), d_sh(48 * hs.n, dev),
      d_ext(std::max(1, hs.n * hs.extras), dev), d_m2(hs.n, dev);
  for (Buffer<float>* b : {&d_pos, &d_ls, &d_rot, &d_lg, &d_sh, &d_ext, &d_m2}) b->fill_zero();
  const goris::GaussianGradView gv{d_pos.data(), d_ls.data(), d_rot.data(), d_lg.data(), d_sh.data(), d_ext.data(), d_m2.data()};

  auto sync = [dev] { goris::device_synchronize(dev); };
  std::vector<double> pre, bin, blend, bblend, bgauss, fwd_cpu, bwd_cpu;
  std::unique_ptr<goris::RasterOutput> out;
  Result r;
  const goris::Timing tf = goris::time_repeated(
      [&] {
        const double c0 = process_cpu_ms();
        out = std::make_unique<goris::RasterOutput>(goris::rasterize(v, cam, rs, dev));
        fwd_cpu.push_back(process_cpu_ms() - c0);
        pre.push_back(out->state.times.preprocess), bin.push_back(out->state.times.binning);
        blend.push_back(out->state.times.blend);
      },
      iters, 1, sync);
  const goris::Timing tb = goris::time_repeated(
      [&] {
        const double c0 = process_cpu_ms();
        goris::rasterize_backward(v, out->state, go, gv);
        bwd_cpu.push_back(process_cpu_ms() - c0);
        bblend.push_back(out->state.times.backward_blend), bgauss.push_back(out->state.times.backward_gaussians);
      },
      iters, 1, sync);
  r.fwd = tf.median_ms, r.bwd = tb.median_ms;
  // Drop the warm-up call's CPU time (time_repeated runs one untimed call first).
  fwd_cpu.erase(fwd_cpu.begin()), bwd_cpu.erase(bwd_cpu.begin());
  r.fwd_cpu = goris::median_of(fwd_cpu), r.bwd_cpu = goris::median_of(bwd_cpu);
  r.pre = goris::median_of(pre), r.bin = goris::median_of(bin), r.blend = goris::median_of(blend);
  r.bblend = goris::median_of(bblend), r.bgauss = goris::median_of(bgauss);
  r.instances = out->state.n_instances;
  // The rasterizer's own buffers at the peak of the backward pass: forward state and G-buffer, the sort's
  // keys and values (twice: radix sort ping-pong) and the per-instance gradient slots.
  const goris::RasterState& st = out->state;
  const goris::GBuffer& gb = out->gbuffer;
  std::size_t bytes = st.radii.bytes() + st.means2d.bytes() + st.conics.bytes() + st.opacities.bytes() +
                      st.colors.bytes() + st.depths.bytes() + st.depth_planes.bytes() + st.normals.bytes() +
                      st.offsets.bytes() + st.tile_rects.bytes() + st.sorted_gauss.bytes() + st.sorted_slot.bytes() +
                      st.tile_ranges.bytes() + st.final_T.bytes() + st.n_contrib.bytes() + st.median_index.bytes();
  bytes += gb.color.bytes() + gb.alpha.bytes() + gb.depth.bytes() + gb.median_depth.bytes() + gb.normal.bytes() +
           gb.extras.bytes();
  bytes += std::max(st.n_instances * 2 * (8 + 4 + 4), st.n_instances * std::size_t(15 + hs.extras) * 4);
  r.mib = double(bytes) / (1024.0 * 1024.0);
  return r;
}

void run_raster_bench(int res, int n, int iters, int extras, int threads, const std::string& device) {
  if (res < 16 || res > 8192) throw goris::Error("bench raster", "--res must be in 16..8192");
  if (threads < 0) throw goris::Error("bench raster", "--threads must be 0 (all) or positive");
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const int used = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  if (n < 1) throw goris::Error("bench raster", "--gaussians must be positive");
  if (iters < 1) throw goris::Error("bench raster", "--iters must be positive");
  std::vector<Device> devs;
  if (device == "all") {
    devs.push_back(Device::CPU);
    if (goris::cuda_device_count() > 0) devs.push_back(Device::CUDA);
  } else {
    devs.push_back(goris::resolve_device(device));
  }
  const HostScene hs = make_scene(n, extras, 7);
  std::printf("# goris bench raster: %dx%d, %d Gaussians (SH degree 3, %d extras), median of %d iterations\n", res,
              res, n, extras, iters);
  std::printf("# CPU: %s, %d worker thread(s)\n# CUDA: %s\n", goris::cpu_description().c_str(), used,
              goris::cuda_device_description().c_str());
  std::printf("# wall ms per pass and stage; \"cpu ms\": process CPU time of fwd+bwd (all threads)\n\n");
  std::printf("| device | forward ms | backward ms | fwd+bwd ms | fwd+bwd cpu ms | preprocess | binning | blend "
              "| bwd blend | bwd gaussians | instances | raster MiB |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Result> res_all;
  for (Device d : devs) {
    const Result r = run(d, hs, res, iters);
    res_all.push_back(r);
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %zu | %.1f |\n",
                goris::device_name(d), r.fwd, r.bwd, r.fwd + r.bwd, r.fwd_cpu + r.bwd_cpu, r.pre, r.bin, r.blend,
                r.bblend, r.bgauss, r.instances, r.mib);
  }
  if (res_all.size() == 2)
    std::printf("\nCPU/CUDA: forward %.1fx, backward %.1fx\n", res_all[0].fwd / res_all[1].fwd, res_all[0].bwd / res_all[1].bwd);
  std::printf("\npeak memory: %s\n", goris::peak_memory_text().c_str());
}

void setup_bench_raster(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto* c = bench.add_subcommand("raster", "G-buffer rasterizer forward and backward on a synthetic scene");
  auto res = std::make_shared<int>(256);
  auto n = std::make_shared<int>(50000);
  auto iters = std::make_shared<int>(20);
  auto extras = std::make_shared<int>(0);
  auto threads = std::make_shared<int>(0);
  auto device = std::make_shared<std::string>("all");
  c->add_option("--res", *res, "image width and height")->capture_default_str();
  c->add_option("--gaussians", *n, "number of Gaussians")->capture_default_str();
  c->add_option("--iters", *iters, "timed iterations (median reported)")->capture_default_str();
  c->add_option("--extras", *extras, "extra per-Gaussian channels blended")->capture_default_str();
  c->add_option("--threads", *threads, "CPU worker threads (0 = all cores)")->capture_default_str();
  c->add_option("--device", *device, "all | auto | cpu | cuda")->capture_default_str();
  c->callback([=] { run_raster_bench(*res, *n, *iters, *extras, *threads, *device); });
}

}  // namespace
GORIS_COMMAND(82, setup_bench_raster);
