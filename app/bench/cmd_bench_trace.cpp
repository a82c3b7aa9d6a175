// `goris bench trace`: rays per second of the Gaussian tracer on the fixture scene (8,000 Gaussians of
// ../shared/fixtures/rasterizer_garden): the fixture's 1,000 camera rays and 1,000 random rays, and a full
// camera image, forward and backward, per backend and round size, with the mean hits per ray, build and
// refit times and the machine, so every number carries its conditions.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/bench/bench_child.h"
#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "core/compute/buffer.h"
#include "core/io/npy.h"
#include "core/compute/bench.h"
#include "core/util/error.h"
#include "render/trace/gaussian_tracer.h"

namespace {

namespace fs = std::filesystem;
using goris::Device;

struct HostScene {
  int n = 0;
  std::vector<float> pos, log_scales, rot, logits, sh;
};

HostScene load_scene(const fs::path& dir) {
  using goris::load_npy;
  const auto means = load_npy(dir / "means.npy"), scales = load_npy(dir / "scales.npy"),
             quats = load_npy(dir / "quats_wxyz.npy"), opac = load_npy(dir / "opacities.npy"), sh = load_npy(dir / "sh.npy");
  HostScene s;
  s.n = int(means.shape.at(0));
  if (scales.data.size() != 3 * std::size_t(s.n) || quats.data.size() != 4 * std::size_t(s.n) ||
      opac.data.size() != std::size_t(s.n) || sh.data.size() != 48 * std::size_t(s.n))
    throw goris::Error(dir.string(), "fixture arrays disagree on the Gaussian count");
  for (double v : means.data) s.pos.push_back(float(v));
  for (double v : scales.data) s.log_scales.push_back(float(std::log(v)));
  for (double v : quats.data) s.rot.push_back(float(v));
  for (double v : opac.data) s.logits.push_back(float(std::log(v / (1 - v))));
  for (double v : sh.data) s.sh.push_back(float(v));
  return s;
}

struct RaySet {
  std::string name;
  std::vector<float> o, d;
  std::size_t count() const { return o.size() / 3; }
};

// Camera 0's rays through every pixel centre of a w x h image covering the fixture camera's view.
RaySet camera_rays(const fs::path& dir, int w, int h) {
  const auto K = goris::load_npy(dir / "Ks.npy"), V = goris::load_npy(dir / "viewmats.npy");
  const double fx = K.data[0] * w / 162.0, cx = K.data[2] * w / 162.0;
  const double fy = K.data[4] * h / 105.0, cy = K.data[5] * h / 105.0;
  glm::dmat3 R;  // world-to-camera rotation, glm column-major
  glm::dvec3 t;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R[c][r] = V.data[4 * r + c];
    t[r] = V.data[4 * r + 3];
  }
  const glm::dvec3 centre = -glm::transpose(R) * t;
  RaySet rs{std::to_string(w) + "x" + std::to_string(h) + " camera rays", {}, {}};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::dvec3 dc((x + 0.5 - cx) / fx, (y + 0.5 - cy) / fy, 1.0);
      const glm::dvec3 d = glm::normalize(glm::transpose(R) * dc);
      for (int k = 0; k < 3; ++k) {
        rs.o.push_back(float(centre[k]));
        rs.d.push_back(float(d[k]));
      }
    }
  return rs;
}

std::vector<RaySet> fixture_rays(const fs::path& tracer_dir) {
  const auto o = goris::load_npy(tracer_dir / "rays_o.npy"), d = goris::load_npy(tracer_dir / "rays_d.npy");
  const std::size_t n = o.data.size() / 3, half = n / 2;
  RaySet cam{"fixture camera rays", {}, {}}, rnd{"fixture random rays", {}, {}};
  for (std::size_t i = 0; i < 3 * n; ++i) {
    RaySet& s = i < 3 * half ? cam : rnd;
    s.o.push_back(float(o.data[i]));
    s.d.push_back(float(d.data[i]));
  }
  return {cam, rnd};
}

// Rays per second of process CPU time (all threads): a number that holds on a machine shared with other
// work, where wall-clock medians do not.
double mrays_per_cpu_second(const std::function<void()>& fn, std::size_t rays, int repeats) {
  const std::clock_t t0 = std::clock();
  for (int i = 0; i < repeats; ++i) fn();
  const double s = double(std::clock() - t0) / CLOCKS_PER_SEC;
  return s > 0 ? double(rays) * repeats / s * 1e-6 : 0.0;
}

std::string fixed3(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

struct Config {
  std::string name;
  Device device;
  goris::TraceSettings settings;
};

void run_bench(const fs::path& shared, int image, int repeats) {
  const fs::path rg = shared / "fixtures/rasterizer_garden", tg = shared / "fixtures/tracer_garden";
  if (!fs::exists(rg / "means.npy") || !fs::exists(tg / "rays_o.npy"))
    throw goris::Error(shared.string(), "fixtures/rasterizer_garden and fixtures/tracer_garden not found (pass --shared)");
  const HostScene hs = load_scene(rg);
  std::vector<RaySet> sets = fixture_rays(tg);
  sets.push_back(camera_rays(rg, image, image));

  std::vector<Config> configs;
  for (int k : {16, 32, 64, 128, 1 << 20}) {
    goris::TraceSettings s;
    s.hits_per_round = k;
    configs.push_back({"cpu embree k=" + (k > 100000 ? std::string("all") : std::to_string(k)), Device::CPU, s});
  }
  goris::TraceSettings lb;
  lb.cpu_accel = goris::TraceAccel::Lbvh;
  configs.push_back({"cpu lbvh k=128", Device::CPU, lb});
  if (goris::cuda_device_count() > 0) configs.push_back({"cuda lbvh", Device::CUDA, {}});

  std::printf("# goris bench trace: %d Gaussians (rasterizer_garden), median of %d runs\n", hs.n, repeats);
  std::printf("# CPU: %s\n# CUDA: %s\n\n", goris::cpu_description().c_str(), goris::cuda_device_description().c_str());
  std::printf("| backend | rays | n | hits/ray | forward Mrays/s | backward Mrays/s | forward Mrays/cpu-s | "
              "backward Mrays/cpu-s | build ms | refit ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Config& c : configs) {
    const Device d = c.device;
    auto sync = [d] { goris::device_synchronize(d); };
    goris::Buffer<float> pos(hs.pos, d), ls(hs.log_scales, d), rot(hs.rot, d), lg(hs.logits, d), sh(hs.sh, d);
    goris::GaussianView v;
    v.count = hs.n;
    v.positions = pos.data();
    v.log_scales = ls.data();
    v.rotations = rot.data();
    v.opacity_logits = lg.data();
    v.sh = sh.data();
    v.sh_degree = 3;
    goris::TraceSettings full = c.settings;
    full.refit = false;
    goris::GaussianTracer tracer(d, full), refitter(d, c.settings);
    const auto t_build = goris::time_repeated([&] { tracer.build(v); }, repeats, 1, sync);
    refitter.build(v);
    const auto t_refit = goris::time_repeated([&] { refitter.build(v); }, repeats, 1, sync);
    goris::Buffer<float> gpos(3 * std::size_t(hs.n), d), gsh(48 * std::size_t(hs.n), d);
    goris::GaussianGradView gv;
    gv.positions = gpos.data();
    gv.sh = gsh.data();
    for (const RaySet& rs : sets) {
      const std::size_t n = rs.count();
      goris::Buffer<float> o(rs.o, d), dir(rs.d, d), color(3 * n, d), depth(n, d), alpha(n, d), dorig(3 * n, d);
      goris::Buffer<std::int32_t> hits(n, d);
      std::mt19937 rng(1);
      std::uniform_real_distribution<float> u(-1.f, 1.f);
      std::vector<float> up(3 * n);
      for (auto& x : up) x = u(rng);
      goris::Buffer<float> dcolor(up, d);
      const goris::TraceRays rays{o.data(), dir.data(), n, 0.0f};
      auto fwd = [&] {
        tracer.trace(rays, goris::TraceOutputs{color.data(), depth.data(), alpha.data(), nullptr, hits.data()});
      };
      auto bwd = [&] {
        tracer.backward(rays, goris::TraceOutputGrads{dcolor.data(), depth.data(), nullptr, nullptr}, gv,
                        goris::TraceRayGrads{dorig.data(), nullptr});
      };
      const auto t_fwd = goris::time_repeated(fwd, repeats, 1, sync);
      const auto t_bwd = goris::time_repeated(bwd, repeats, 1, sync);
      const bool cpu = d == Device::CPU;
      const double cpu_fwd = cpu ? mrays_per_cpu_second(fwd, n, repeats) : 0.0;
      const double cpu_bwd = cpu ? mrays_per_cpu_second(bwd, n, repeats) : 0.0;
      double sum_hits = 0;
      for (auto h : hits.to_host()) sum_hits += h;
      std::printf("| %s | %s | %zu | %.1f | %.3f | %.3f | %s | %s | %.2f | %.2f |\n", c.name.c_str(), rs.name.c_str(),
                  n, sum_hits / double(n), n / t_fwd.median_ms * 1e-3, n / t_bwd.median_ms * 1e-3,
                  cpu ? fixed3(cpu_fwd).c_str() : "-", cpu ? fixed3(cpu_bwd).c_str() : "-", t_build.median_ms,
                  t_refit.median_ms);
    }
  }
  std::printf("\nbackward: dL/dcolour random, dL/ddepth = depth; gradients to positions, SH and ray origins\n");
  std::printf("peak memory: %s\n", goris::peak_memory_text().c_str());
}

void setup_bench_trace(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto* c = bench.add_subcommand("trace", "Gaussian ray tracer: rays/s forward and backward on the fixture scene");
  auto shared = std::make_shared<std::string>(std::string(GORIS_RESOURCE_DIR) + "/../../shared");
  auto image = std::make_shared<int>(256);
  auto repeats = std::make_shared<int>(5);
  c->add_option("--shared", *shared, "folder holding fixtures/rasterizer_garden and fixtures/tracer_garden")
      ->capture_default_str();
  c->add_option("--image", *image, "side of the square camera image traced")->capture_default_str()->check(goris::cli::whole(1, 4096));
  c->add_option("--repeats", *repeats, "timed runs (median reported)")->capture_default_str()->check(goris::cli::whole(1, 1000));
  c->callback([shared, image, repeats] { run_bench(*shared, *image, *repeats); });
}

}  // namespace
GORIS_COMMAND(83, setup_bench_trace);
