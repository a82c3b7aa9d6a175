// `goris bench intrinsic RUN`: the time split of one intrinsic training iteration (rasterize, reflection
// rays, trace, screen-space filter + net, shading; and the backward of each) on a real training view of a
// trained intrinsic run, with the rays traced per second, the Gaussian count, the resolution, the threads
// and the machine, and the reflection rays traced and saved by coarse tracing (--coarse-tracing both
// compares the two set-ups on the same frame: time and PSNR). Medians over --repeats iterations (after one
// warm-up), stages timed with the device synchronised around each; "cpu ms" is the process CPU time of the
// whole iteration (all threads). --resolution renders the view at another width than the run trained at
// (the Gaussians do not depend on it), e.g. the 512 px frame rate of a run trained at 128 px. --kernels
// adds the time of every launch site (parallel_for and the timed blocks around the rasterizer's blend, the
// tracer on the CPU, sorts and scans) over the timed iterations (core/compute/kernel_profile.h).
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/bench/bench_child.h"
#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "core/compute/kernel_profile.h"
#include "core/compute/memory.h"
#include "core/io/dataset.h"
#include "train/losses/image_losses.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "core/compute/bench.h"
#include "core/util/error.h"
#include "core/util/median.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/setup/run_renderer.h"

namespace {
using namespace goris;

double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

// Medians of one renderer set-up over the timed iterations, and its last shaded colour.
struct Measured {
  std::vector<double> raster, rays, trace, filter, shade, shade_b, filter_b, trace_b, raster_b, total, cpu;
  std::size_t traced = 0, glossy = 0, net_pixels = 0, pixels = 0;
  std::vector<float> color;
};

Measured measure(IntrinsicRenderer& ir, GaussianModel& model, const TrainView& v, Device device, int repeats,
                 bool kernels) {
  const size_t hw = size_t(v.camera.width) * v.camera.height;
  Measured m;
  for (int r = 0; r <= repeats; ++r) {
    ir.set_profile(r > 0);
    kernel_profile::enable(kernels && r > 0);
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const RenderedImages out = ir.forward(model.view(true), v.camera);
    std::vector<float> color(3 * hw), g(3 * hw);
    device_copy(color.data(), Device::CPU, out.color, device, color.size() * sizeof(float));
    for (size_t i = 0; i < g.size(); ++i) g[i] = (color[i] > v.image[i] ? 1.0f : -1.0f) / float(g.size());
    Buffer<float> dg(g, device);
    model.zero_grad();
    ImageGradients d;
    d.color = dg.data();
    ir.backward(model.view(true), d, model.grad_view(true));
    model.backprop_extras();
    device_synchronize(device);
    kernel_profile::enable(false);
    if (r == 0) continue;  // warm-up (allocations, BVH build)
    const IntrinsicTimes& t = ir.times();
    m.total.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    m.cpu.push_back(1000 * (cpu_seconds() - c0));
    m.raster.push_back(t.raster);
    m.rays.push_back(t.rays);
    m.trace.push_back(t.trace);
    m.filter.push_back(t.filter);
    m.shade.push_back(t.shade);
    m.shade_b.push_back(t.shade_back);
    m.filter_b.push_back(t.filter_back);
    m.trace_b.push_back(t.trace_back);
    m.raster_b.push_back(t.raster_back);
    m.traced = t.rays_traced;
    m.glossy = t.rays_glossy;
    m.net_pixels = t.net_pixels;
    m.pixels = t.pixels;
    m.color = std::move(color);
  }
  return m;
}

double psnr(const std::vector<float>& a, const std::vector<float>& b) {
  return psnr_from_mse(mse<float>(a.data(), b.data(), std::min(a.size(), b.size())));
}

// The shaded frame (the forward stages) and the backward, each the sum of its stages' medians.
double forward_ms(const Measured& m) {
  return median_of(m.raster) + median_of(m.rays) + median_of(m.trace) + median_of(m.filter) + median_of(m.shade);
}
double backward_ms(const Measured& m) {
  return median_of(m.raster_b) + median_of(m.trace_b) + median_of(m.filter_b) + median_of(m.shade_b);
}

double saved_percent(const Measured& m) { return m.glossy ? 100.0 * (1.0 - double(m.traced) / double(m.glossy)) : 0.0; }

void print_stages(const char* name, const Measured& m) {
  std::printf("coarse tracing %s: %zu of %zu glossy pixels traced (%.1f %% saved)\n", name, m.traced, m.glossy,
              saved_percent(m));
  std::printf("roughness net on %zu of %zu pixels (%.1f %%: the surface pixels' window)\n\n", m.net_pixels, m.pixels,
              m.pixels ? 100.0 * double(m.net_pixels) / double(m.pixels) : 0.0);
  std::printf("| stage | forward ms | backward ms |\n|---|---|---|\n");
  std::printf("| rasterize (G-buffer) | %.2f | %.2f |\n", median_of(m.raster), median_of(m.raster_b));
  std::printf("| reflection rays (+ coarse selection) | %.2f | (in trace) |\n", median_of(m.rays));
  std::printf("| trace | %.2f | %.2f |\n", median_of(m.trace), median_of(m.trace_b));
  std::printf("| filter + net | %.2f | %.2f |\n", median_of(m.filter), median_of(m.filter_b));
  std::printf("| shading | %.2f | %.2f |\n", median_of(m.shade), median_of(m.shade_b));
  const double tr = median_of(m.trace);
  std::printf("\niteration (renderer only, wall): median %.1f ms; process CPU %.1f ms; trace %.3f Mrays/s forward\n\n",
              median_of(m.total), median_of(m.cpu), tr > 0 ? double(m.traced) / tr * 1e-3 : 0.0);
}

void run_bench_intrinsic(const std::string& run, int view_index, int repeats, int threads, const std::string& dev,
                         const std::string& coarse, int coarse_max_level, int resolution, bool kernels) {
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const std::filesystem::path run_dir = std::filesystem::absolute(run);
  TrainConfig config = read_run_config(run_dir);
  if (coarse_max_level > 0) config.intrinsic.coarse_max_level = coarse_max_level;
  if (config.mode != TrainMode::Intrinsic)
    throw Error(run_dir.string(), std::string("is a ") + enum_name(config.mode) + " run; train with --mode intrinsic");
  const Device device = resolve_device(dev);
  DatasetOptions dopt = dataset_options(config);
  if (resolution > 0) dopt.target_width = resolution;
  const Dataset ds = load_dataset(config.input.data, dopt);
  if (view_index < 0 || size_t(view_index) >= ds.train.size())
    throw Error(config.input.data, "has " + std::to_string(ds.train.size()) + " training views; --view " +
                                 std::to_string(view_index) + " does not exist");
  const std::vector<TrainView> views = load_train_views({ds.train[size_t(view_index)]}, dopt);
  const TrainView& v = views[0];
  GaussianModel model = load_run_model(run_dir, device);

  // Which set-ups: the run's own, or coarse tracing forced off / on, or both in turn.
  std::vector<std::pair<std::string, bool>> modes;
  if (coarse == "run") modes.push_back({config.intrinsic.coarse_tracing ? "on" : "off", config.intrinsic.coarse_tracing});
  if (coarse == "off" || coarse == "both") modes.push_back({"off", false});
  if (coarse == "on" || coarse == "both") modes.push_back({"on", true});
  std::vector<Measured> results;
  for (const auto& [name, on] : modes) {
    TrainConfig c = config;
    c.intrinsic.coarse_tracing = on;
    const auto renderer = load_run_renderer(run_dir, c, scene_extent(ds), device);
    kernel_profile::reset();
    results.push_back(measure(*as_intrinsic(renderer.get()), model, v, device, repeats, kernels));
  }

  std::printf("# goris bench intrinsic: one stage-1 iteration with shading (forward + backward)\n");
  std::printf("machine: %s; device %s; threads %d\n", cpu_description().c_str(), device_name(device),
              int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  std::printf("run %s: %zu Gaussians, view %s at %dx%d, env map %d^2, filter %s, coarse max level %d; %d repeats\n\n",
              run_dir.string().c_str(), model.count(), v.name.c_str(), v.camera.width, v.camera.height,
              config.intrinsic.env_resolution, config.intrinsic.screen_space_filter ? "on" : "off",
              config.intrinsic.coarse_max_level, repeats);
  for (size_t i = 0; i < modes.size(); ++i) print_stages(modes[i].first.c_str(), results[i]);
  std::printf("| coarse tracing | rays traced | rays saved | forward ms | backward ms | iteration ms | PSNR vs view (dB) |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (size_t i = 0; i < modes.size(); ++i) {
    const Measured& m = results[i];
    std::printf("| %s | %zu / %zu | %.1f %% | %.1f | %.1f | %.1f | %.2f |\n", modes[i].first.c_str(), m.traced, m.glossy,
                saved_percent(m), forward_ms(m), backward_ms(m), median_of(m.total), psnr(m.color, v.image));
  }
  // The shaded frame alone (the forward stages, each timed between device synchronisations).
  for (size_t i = 0; i < modes.size(); ++i) {
    const double fwd = forward_ms(results[i]);
    std::printf("\ntraced shading frame at %dx%d, coarse tracing %s: %.2f ms forward = %.0f frames per second\n",
                v.camera.width, v.camera.height, modes[i].first.c_str(), fwd, fwd > 0 ? 1000.0 / fwd : 0.0);
  }
  if (results.size() == 2)
    std::printf("\nPSNR of the coarse frame against the fully traced one: %.2f dB\n", psnr(results[1].color, results[0].color));
  if (kernels)
    std::printf("\nlaunch sites over the %d timed iterations (coarse tracing %s):\n\n%s", repeats,
                modes.back().first.c_str(), kernel_profile::markdown_table().c_str());
}

void setup_bench_intrinsic(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto* c = bench.add_subcommand("intrinsic", "Time split of one intrinsic iteration on a trained run's training view");
  auto run = std::make_shared<std::string>();
  auto view = std::make_shared<int>(0);
  auto repeats = std::make_shared<int>(5);
  auto threads = std::make_shared<int>(0);
  auto device = std::make_shared<std::string>("auto");
  auto coarse = std::make_shared<std::string>("run");
  auto coarse_level = std::make_shared<int>(0);
  auto resolution = std::make_shared<int>(0);
  auto kernels = std::make_shared<bool>(false);
  c->add_option("run", *run, "An intrinsic run folder (goris train --mode intrinsic)")->required();
  c->add_option("--view", *view, "Training view index")->capture_default_str();
  c->add_option("--repeats", *repeats, "Timed iterations (median reported)")->capture_default_str()->check(cli::whole(1, 1000));
  c->add_option("--threads", *threads, "CPU threads (0 = all)")->capture_default_str()->check(cli::whole(0, 4096));
  cli::add_device_option(*c, *device);
  c->add_option("--coarse-tracing", *coarse,
                "run (as the run was trained) | on | off | both (off then on, with the PSNR between the two frames)")
      ->capture_default_str()
      ->check(CLI::IsMember({"run", "on", "off", "both"}));
  c->add_option("--coarse-max-level", *coarse_level, "Largest coarse-tracing block 2^N pixels wide (0 = the run's)")
      ->capture_default_str()
      ->check(cli::whole(0, 3));
  c->add_option("--resolution", *resolution, "Render the view at this width in pixels (0 = the run's)")
      ->capture_default_str()
      ->check(cli::whole(0, 8192));
  c->add_flag("--kernels", *kernels,
              "Also time every launch site (parallel_for, blend, CPU tracer, sorts, scans) over the timed iterations (the last coarse-tracing set-up; "
              "on CUDA each launch is synchronised, so the stage times grow)");
  c->callback([=] {
    run_bench_intrinsic(*run, *view, *repeats, *threads, *device, *coarse, *coarse_level, *resolution, *kernels);
  });
}

}  // namespace
GORIS_COMMAND(84, setup_bench_intrinsic);
