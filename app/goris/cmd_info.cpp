// `goris info PATH [--against REF]`: what a data set, a run folder (`goris train` or its removal/) or a model
// file (.ply, .compressed.ply, .spz, .splat, .glb) contains, without decoding any image (headers only). With --against, how far the model is from another
// model file, attribute by attribute (core/io/splat_compare.h): what an export's quantization changed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "core/io/dataset.h"
#include "core/io/ply.h"
#include "core/io/splat_compare.h"
#include "core/io/splat_formats.h"
#include "core/util/error.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"

namespace {
namespace fs = std::filesystem;
using goris::Camera;
using goris::View;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string count_of(size_t have, size_t of) { return std::to_string(have) + "/" + std::to_string(of); }

template <class Pred>
size_t count_views(const std::vector<View>& views, Pred p) {
  return size_t(std::count_if(views.begin(), views.end(), p));
}

std::string intrinsics_line(const Camera& c) {
  return "fx " + fmt("%.4g", c.fx) + "  fy " + fmt("%.4g", c.fy) + "  cx " + fmt("%.4g", c.cx) + "  cy " + fmt("%.4g", c.cy);
}

std::string distortion_line(const Camera& c) {
  if (!c.has_distortion()) return "none";
  const auto& d = c.dist;
  return "k1 " + fmt("%.6g", d.k1) + "  k2 " + fmt("%.6g", d.k2) + "  k3 " + fmt("%.6g", d.k3) + "  p1 " +
         fmt("%.6g", d.p1) + "  p2 " + fmt("%.6g", d.p2);
}

bool same_intrinsics(const Camera& a, const Camera& b) {
  auto near = [](float x, float y) { return std::abs(x - y) <= 1e-4f * std::max(1.0f, std::abs(x)); };
  return a.width == b.width && a.height == b.height && near(a.fx, b.fx) && near(a.fy, b.fy) && near(a.cx, b.cx) &&
         near(a.cy, b.cy) && near(a.dist.k1, b.dist.k1) && near(a.dist.k2, b.dist.k2) && near(a.dist.k3, b.dist.k3) &&
         near(a.dist.p1, b.dist.p1) && near(a.dist.p2, b.dist.p2);
}

void print_dataset(const goris::Dataset& d, const goris::DatasetOptions& o) {
  std::vector<const View*> all;
  for (const auto* split : {&d.train, &d.test})
    for (const View& v : *split) all.push_back(&v);

  std::printf("data set:    %s\n", d.root.string().c_str());
  std::printf("format:      %s (%s)\n", d.format.c_str(), d.source.string().c_str());
  std::string views = std::to_string(d.view_count()) + " (" + std::to_string(d.train.size()) + " train, " +
                      std::to_string(d.test.size()) + " test";
  if (d.format != "nerf-synthetic")
    views += o.test_every > 0 ? "; views 0, " + std::to_string(o.test_every) + ", " + std::to_string(2 * o.test_every) + "... held out for testing"
                              : "; no test hold-out";
  std::printf("views:       %s)\n", views.c_str());

  std::map<std::pair<int, int>, size_t> sizes, source_sizes;
  for (const View* v : all) {
    ++sizes[{v->camera.width, v->camera.height}];
    ++source_sizes[{v->source_width, v->source_height}];
  }
  auto size_list = [](const std::map<std::pair<int, int>, size_t>& m) {
    std::string s;
    for (const auto& [wh, n] : m)
      s += (s.empty() ? "" : ", ") + std::to_string(wh.first) + "x" + std::to_string(wh.second) +
           (m.size() > 1 ? " (" + std::to_string(n) + " views)" : "");
    return s;
  };
  std::string res = size_list(sizes);
  if (sizes != source_sizes) res += "  (files: " + size_list(source_sizes) + ")";
  std::printf("resolution:  %s\n", res.c_str());

  const Camera& first = all.front()->camera;
  const bool uniform = std::all_of(all.begin(), all.end(), [&](const View* v) { return same_intrinsics(v->camera, first); });
  std::printf("intrinsics:  %s%s\n", intrinsics_line(first).c_str(), uniform ? "" : "  (first view; they vary)");
  std::printf("distortion:  %s\n", distortion_line(first).c_str());

  auto has_object = [](const View& v) { return v.object_mask.has_value(); };
  auto has_glossy = [](const View& v) { return v.glossy_mask.has_value(); };
  auto has_full = [](const View& v) { return v.full_image.has_value(); };
  std::printf("object masks: %s train, %s test\n", count_of(count_views(d.train, has_object), d.train.size()).c_str(),
              count_of(count_views(d.test, has_object), d.test.size()).c_str());
  std::printf("glossy masks: %s train, %s test\n", count_of(count_views(d.train, has_glossy), d.train.size()).c_str(),
              count_of(count_views(d.test, has_glossy), d.test.size()).c_str());
  if (const size_t full = count_views(d.test, has_full))
    std::printf("full images: %s test (the test views rendered with the target)\n", count_of(full, d.test.size()).c_str());
  std::printf("sfm points:  %zu\n", d.points.size());
  if (d.depth_range) std::printf("depth range: %.4g .. %.4g\n", d.depth_range->x, d.depth_range->y);
  const goris::SceneBounds b = d.camera_bounds();
  std::printf("cameras:     centre (%.4g, %.4g, %.4g), extent %.4g\n", b.center.x, b.center.y, b.center.z, b.radius);
}

// The iteration in a checkpoint's name (iter_<8 digits>.ckpt), without reading the file; -1 when not one.
int checkpoint_iteration(const fs::path& ckpt) {
  const std::string stem = ckpt.stem().string();
  if (stem.rfind("iter_", 0) != 0) return -1;
  try {
    return std::stoi(stem.substr(5));
  } catch (const std::exception&) {
    return -1;
  }
}

// How far a run got: finished, the checkpoint a --resume starts from, none yet, or why none is usable.
std::string run_progress(const fs::path& run, const goris::TrainConfig& c) {
  std::optional<fs::path> ckpt;
  try {
    ckpt = goris::latest_checkpoint(run);
  } catch (const goris::Error& e) {  // checkpoints, none intact: which and why, instead of failing
    return e.what();
  }
  const int at = ckpt ? checkpoint_iteration(*ckpt) : -1;
  if (fs::exists(goris::run_ply_path(run)) && (at < 0 || at >= c.iterations))
    return "finished, " + std::to_string(c.iterations) + " iterations";
  if (at >= 0)
    return "stopped at iteration " + std::to_string(at) + " of " + std::to_string(c.iterations) + " (" +
           ckpt->filename().string() + "); --resume carries on from there";
  return "no checkpoint yet (" + std::to_string(c.iterations) + " iterations planned)";
}

// A run folder: where its data set is, what it trains, how far it got (finished, or the checkpoint a
// --resume starts from), its model, and the state of a removal inside it.
void print_run(const fs::path& run, bool nested = false) {
  const goris::TrainConfig c = goris::read_run_config(run);
  const char* in = nested ? "  " : "";
  if (!nested) {
    std::printf("run:         %s\n", run.string().c_str());
    std::printf("data set:    %s%s\n", c.input.data.c_str(),
                c.input.data.empty() || fs::exists(c.input.data)
                    ? ""
                    : "  (not found: moved? other commands read it from config.json; --data NEW_FOLDER points them "
                      "at its new place)");
    std::printf("mode:        %s\n", enum_name(c.mode));
  }
  const fs::path ply = goris::run_ply_path(run);
  std::printf("%s%-13s%s\n", in, "progress:", run_progress(run, c).c_str());
  if (fs::exists(ply)) {
    std::printf("%smodel:       %s\n", in, ply.string().c_str());
    std::printf("%s", goris::gaussians_summary(ply).c_str());
  }
  if (nested) return;
  const fs::path removal = run / "removal";
  if (!fs::exists(goris::run_config_path(removal))) {
    std::printf("removal:     %s\n", fs::is_directory(removal) ? "started, not fine-tuned yet (goris remove carries on)" : "none");
    return;
  }
  std::printf("removal:     %s\n", removal.string().c_str());
  std::ifstream rf(removal / "report.json");
  if (rf) {
    nlohmann::json r;
    try {
      r = nlohmann::json::parse(rf);
      std::printf("  selected %d of %d Gaussians, %d after the fine-tune; %d mirror twins, %d under the target, %d "
                  "reflection pixels (%d of them kept their photo)\n",
                  r.value("selected", 0), r.value("gaussians_before", 0), r.value("gaussians_after", 0),
                  r.value("mirror_twins", 0), r.value("underside", 0), r.value("reflection_pixels", 0),
                  r.value("reflection_photo_pixels", 0));
      if (r.contains("options") && r["options"].contains("fill_truth"))
        std::printf("  a measurement, not a removal: fine-tuned with the true images %s (--fill-truth)\n",
                    r["options"]["fill_truth"].get<std::string>().c_str());
      if (r.contains("photo_targets_against_truth")) {
        const nlohmann::json& t = r["photo_targets_against_truth"];
        std::printf("  the photos it trains on carry %.3f of the target's imprint as taken, %.3f as trained "
                    "(dereflected, relit: %.3f -> %.3f on the %d pixels changed)\n",
                    t.value("photos_as_taken", 0.0), t.value("photos_as_trained", 0.0), t.value("changed_as_taken", 0.0),
                    t.value("changed_as_trained", 0.0), t.value("changed_pixels", 0));
      }
    } catch (const nlohmann::json::exception&) {
      std::printf("  report.json: not readable JSON\n");
    }
  }
  print_run(removal, /*nested=*/true);
}

void setup_info(CLI::App& root) {
  auto* c = root.add_subcommand(
      "info", "Summarise a data set (NeRF-synthetic, instant-ngp, COLMAP, LLFF), a run folder or a model file (.ply, "
      ".compressed.ply, .spz, .splat, .glb)");
  static std::string path, against, match = "position";
  static int resolution = 0;
  static float downscale = 1.0f;
  static int test_every = 8;
  c->add_option("path", path, "data set folder, one of its camera files, a run folder, or a model file")->required();
  auto* ag = c->add_option("--against", against,
                           "a model file to compare PATH with: max and mean error per attribute (position, log scale, "
                           "rotation angle, opacity, SH DC and rest)");
  c->add_option("--match", match,
                "how Gaussians pair up for --against: position (nearest, for writers that reorder) or index")
      ->check(CLI::IsMember({"position", "index"}))
      ->needs(ag);
  auto* r = c->add_option("--resolution", resolution, "load images at this width in pixels (height keeps the aspect)")
                ->check(goris::cli::whole(1, 65536));
  c->add_option("--downscale", downscale, "divide the image size by this factor")->check(goris::cli::real(1, 1000))->excludes(r);
  c->add_option("--test-every", test_every,
                "hold out every N-th view for testing (instant-ngp, COLMAP, LLFF); 0 = none")
      ->check(goris::cli::whole(0, goris::cli::kIntMax))
      ->capture_default_str();
  c->callback([] {
    const fs::path p(path);
    if (goris::is_splat_file_name(p)) {
      std::printf("%s", goris::gaussians_summary(p).c_str());
      if (!against.empty()) {
        const goris::GaussianPly ref = goris::read_gaussians(against), got = goris::read_gaussians(p);
        if (ref.count != got.count)
          throw goris::Error(p.string(), std::to_string(got.count) + " Gaussians, " + against + " has " +
                                             std::to_string(ref.count) + ": cannot compare");
        const auto order = match == "position" ? goris::match_by_position(ref, got) : std::vector<uint32_t>{};
        std::printf("against %s (matched by %s):\n%s", against.c_str(), match.c_str(),
                    goris::compare_models(ref, got, order).table().c_str());
      }
      return;
    }
    if (!against.empty()) throw goris::Error(p.string(), "--against needs a model file, not a data set or a run");
    if (fs::is_directory(p) && fs::exists(goris::run_config_path(p))) {
      print_run(p);
      return;
    }
    goris::DatasetOptions o;
    o.target_width = resolution;
    o.downscale = downscale;
    o.test_every = test_every;
    const goris::Dataset d = goris::load_dataset(p, o);
    for (const auto& w : d.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    print_dataset(d, o);
  });
}
}  // namespace
GORIS_COMMAND(10, setup_info);
