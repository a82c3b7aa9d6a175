// `goris render RUN --split test --out DIR [--maps] [--model FILE]`: renders a trained run from the data set's
// cameras (at the training resolution). With --maps every G-buffer channel is written as a viewable PNG too.
// --model renders a model file (.ply, .compressed.ply, .spz, .splat, .glb: core/io/splat_formats.h) in place of the
// run's own, with the run's cameras and renderer (say, an export read back).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli_common/command.h"
#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/io/splat_formats.h"
#include "core/scene/gaussians.h"
#include "train/losses/depth_normal_loss.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "train/run/run_output_guard.h"
#include "core/util/error.h"
#include "render/maps/gbuffer_maps.h"
#include "render/raster/rasterizer.h"
#include "train/radiance/raster_renderer.h"
#include "train/setup/run_renderer.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "core/compute/memory.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, split = "test", out, device = "auto", model, data;
  bool maps = false;
};

// The channels of an extras G-buffer worth a picture each: (name, first channel, channel count).
struct ExtraMap {
  const char* name;
  int first, count;
};
constexpr ExtraMap kExtraMaps[] = {{"diffuse", extra::kDiffuse, 3}, {"fresnel", extra::kFresnel, 3},
                                   {"roughness", extra::kRoughness, 1}, {"region", extra::kRegion, 1},
                                   {"label", extra::kLabel, 1}};

void run_render(const Options& o) {
  const fs::path run_dir = fs::absolute(o.run);
  const TrainConfig config = read_run_config_with_data(run_dir, o.data);
  const fs::path out = fs::absolute(o.out);
  check_output_dir(out, run_output_guard(run_dir, config));  // never into the data set or over the run's files
  const Device device = resolve_device(o.device);
  const Dataset ds = load_dataset(config.input.data, dataset_options(config));
  const std::vector<View>& views = o.split == "test" ? ds.test : ds.train;
  if (views.empty()) throw Error(config.input.data, "the data set has no " + o.split + " views");
  std::string source = o.model;
  GaussianModel model = o.model.empty() ? load_run_model(run_dir, device, &source)
                                        : GaussianModel::from_ply(read_gaussians(o.model), device);
  std::printf("rendering %zu %s views of %s (%zu Gaussians, %s) on %s -> %s\n", views.size(), o.split.c_str(),
              run_dir.string().c_str(), model.count(), source.c_str(), device_name(device), out.string().c_str());

  const auto renderer = load_run_renderer(run_dir, config, scene_extent(ds), device);
  IntrinsicRenderer* intrinsic = as_intrinsic(renderer.get());
  double total_ms = 0;
  for (const View& v : views) {
    const Camera& cam = v.camera;
    const int w = cam.width, h = cam.height;
    const size_t hw = size_t(w) * h;
    const auto t0 = std::chrono::steady_clock::now();
    const GaussianView gv = model.view(o.maps || renderer->wants_extras());
    std::vector<float> color(3 * hw);
    if (intrinsic && o.maps) {
      const IntrinsicMaps im = intrinsic->render_maps(gv, cam);
      color = im.color;
      save_png(out / (v.name + "_sh_color.png"), from_planar(im.sh_color.data(), 3, w, h));
      save_png(out / (v.name + "_glossy.png"), from_planar(im.glossy.data(), 3, w, h));
      save_png(out / (v.name + "_indirect.png"), from_planar(im.indirect.data(), 3, w, h));
      save_png(out / (v.name + "_visibility.png"), from_planar(im.visibility.data(), 1, w, h));
      save_png(out / (v.name + "_env_light.png"), from_planar(im.env.data(), 3, w, h));
      if (!im.screen_roughness.empty())
        save_png(out / (v.name + "_screen_roughness.png"), from_planar(im.screen_roughness.data(), 1, w, h));
      if (!im.indirect_traced.empty()) {
        save_png(out / (v.name + "_indirect_traced.png"), from_planar(im.indirect_traced.data(), 3, w, h));
        save_png(out / (v.name + "_visibility_traced.png"), from_planar(im.visibility_traced.data(), 1, w, h));
      }
    } else {
      const RenderedImages r = renderer->forward(gv, cam);
      device_copy(color.data(), Device::CPU, r.color, device, color.size() * sizeof(float));
    }
    total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    save_png(out / (v.name + ".png"), from_planar(color.data(), 3, w, h));
    if (!o.maps) continue;
    // The G-buffer of the same view (the intrinsic renderer keeps its own; rasterize for a radiance run).
    const RasterOutput r = intrinsic ? RasterOutput{} : rasterize(gv, cam, RasterRenderer::settings_for(config), device);
    const GBuffer& gb = intrinsic ? intrinsic->last().gbuffer : r.gbuffer;
    const std::vector<float> alpha = gb.alpha.to_host(), depth = gb.depth.to_host(),
                             median = gb.median_depth.to_host(), normal = gb.normal.to_host(),
                             extras = gb.extras.to_host();
    save_png(out / (v.name + "_alpha.png"), from_planar(alpha.data(), 1, w, h));
    save_png(out / (v.name + "_depth.png"), depth_to_turbo(depth.data(), alpha.data(), w, h, true));
    save_png(out / (v.name + "_median_depth.png"), depth_to_turbo(median.data(), alpha.data(), w, h, false));
    save_png(out / (v.name + "_normal.png"), normals_to_rgb(normal.data(), alpha.data(), w, h));
    // The normal the depth map implies (what the depth-normal consistency loss compares against).
    std::vector<float> expected(hw), depth_normal(3 * hw);
    for (size_t p = 0; p < hw; ++p) expected[p] = alpha[p] > 1e-4f ? depth[p] / alpha[p] : 0.0f;
    normal_from_depth<float>(expected.data(), w, h, cam.fx, cam.fy, cam.cx, cam.cy, depth_normal.data());
    save_png(out / (v.name + "_depth_normal.png"), normals_to_rgb(depth_normal.data(), alpha.data(), w, h));
    if (gb.n_extras == extra::kCount)
      for (const ExtraMap& m : kExtraMaps)
        save_png(out / (v.name + "_" + m.name + ".png"), from_planar(extras.data() + size_t(m.first) * hw, m.count, w, h));
  }
  std::printf("%zu images at %dx%d, %.1f ms per render (mean)\n", views.size(), views[0].camera.width,
              views[0].camera.height, total_ms / double(views.size()));
}

void setup_render(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("render", "Render a trained run from the data set's cameras");
  c->add_option("run", o->run, "Run folder written by `goris train`")->required();
  c->add_option("--split", o->split, "Which cameras: test or train")->check(CLI::IsMember({"test", "train"}));
  c->add_option("--out", o->out, "Output folder for the PNG images")->required();
  c->add_flag("--maps", o->maps,
              "Also write every G-buffer channel: alpha, depth and median depth (TURBO on inverse depth), "
              "normal and depth-normal (n*0.5+0.5), diffuse, fresnel, roughness, region, label; intrinsic runs add "
              "sh_color (D), glossy (G), indirect (L_ind'), visibility (V'), env_light (L_dir'), screen_roughness, "
              "indirect_traced and visibility_traced (L_ind and V as traced, before the screen-space filter)");
  c->add_option("--model", o->model,
                "Render this model file (.ply, .compressed.ply, .spz, .splat or .glb) instead of the run's own model");
  cli::add_device_option(*c, o->device);
  cli::add_data_option(*c, o->data);
  c->callback([o] { run_render(*o); });
}

}  // namespace
GORIS_COMMAND(40, setup_render);
