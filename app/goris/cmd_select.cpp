// `goris select RUN (--click VIEW X Y | --masks [DIR] | --labels [--threshold T]) [--grow G] [--out FILE]`:
// chooses the target of object removal and stores it in the run folder (selection.json + selection.npy,
// core/removal/selection_file.h) with preview images (tinted | removed) of a few training views.
//
//   --labels  Gaussians with learned label > T (0.3), closed by the hull of their centres (paper Sec. 3.3)
//   --masks   depth-tested votes of the Gaussian centres in the training views' object masks, then closed
//   --click   the Gaussian a pixel of a training view shows, grown over similar neighbours, then closed
// An empty selection, or one larger than --max-fraction of the scene, is an error that says what to change.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/goris/command.h"
#include "app/goris/number_checks.h"
#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/train/run_folder.h"
#include "core/train/train_setup.h"
#include "core/train/run_output_guard.h"
#include "core/util/error.h"
#include "render/removal/selection.h"
#include "render/train/raster_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, out, device = "auto";
  std::vector<std::string> click;  // VIEW X Y
  std::string masks_dir;
  bool masks = false, labels = false, no_close = false;
  float threshold = 0.3f, min_fraction = 0.5f, max_fraction = 0.5f;
  std::optional<float> grow;
  int previews = 4;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int parse_int(const std::string& s, const char* what) {
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty()) throw Error(std::string("--click: ") + what + " '" + s + "' is not an integer");
  return v;
}

// A training view by name (r_012) or by index into the training views (12).
std::size_t find_view(const std::vector<View>& views, const std::string& key) {
  for (std::size_t i = 0; i < views.size(); ++i)
    if (views[i].name == key) return i;
  std::size_t used = 0;
  long idx = -1;
  try {
    idx = std::stol(key, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == key.size() && idx >= 0 && std::size_t(idx) < views.size()) return std::size_t(idx);
  throw Error("--click", "no training view '" + key + "' (give a name such as " + views.front().name +
                             " or an index 0.." + std::to_string(views.size() - 1) + ")");
}

nlohmann::json summary_json(const SelectionSummary& s) {
  return {{"total", s.total},         {"seeds", s.seeds},     {"outliers", s.outliers},
          {"by_volume", s.by_volume}, {"dropped", s.dropped}, {"selected", s.selected},
          {"volume", volume_kind_name(s.volume)}, {"hull_facets", s.hull_facets}};
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

std::string percent(double f) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f%%", 100.0 * f);
  return b;
}

// Training views for the previews: the clicked one first, then evenly spread ones.
std::vector<std::size_t> preview_views(std::size_t n_views, int wanted, std::optional<std::size_t> first) {
  std::vector<std::size_t> v;
  if (first) v.push_back(*first);
  for (int k = 0; int(v.size()) < wanted && k < wanted; ++k) {
    const std::size_t idx = std::size_t(k) * n_views / std::size_t(std::max(wanted, 1));
    if (std::find(v.begin(), v.end(), idx) == v.end()) v.push_back(idx);
  }
  if (v.size() > std::size_t(std::max(wanted, 0))) v.resize(std::size_t(std::max(wanted, 0)));
  return v;
}

void run_select(const Options& o, int n_methods) {
  if (n_methods != 1) throw Error("goris select: choose exactly one of --click VIEW X Y, --masks [DIR], --labels");
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path run_dir = fs::absolute(o.run);
  const TrainConfig config = read_run_config(run_dir);
  // Never into the data set or over the run's other files (the selection itself is this command's output).
  const fs::path json_path = o.out.empty() ? selection_json_path(run_dir) : fs::absolute(o.out);
  const OutputGuard guard = run_output_guard(run_dir, config, /*keep_selection=*/false);
  check_output_file(json_path, guard);
  check_output_file(json_path.parent_path() / (json_path.stem().string() + ".npy"), guard);
  const Device device = resolve_device(o.device);
  const Dataset ds = load_dataset(config.data, dataset_options(config));
  if (ds.train.empty()) throw Error(config.data, "the data set has no training views");
  std::string source;
  const GaussianModel model = load_run_model(run_dir, device, &source);
  std::printf("selecting in %s: %zu Gaussians from %s\n", run_dir.string().c_str(), model.count(), source.c_str());
  if (model.count() == 0) throw Error(source, "the model has no Gaussians");
  const SelectionPoints pts = selection_points(model);
  const RasterSettings raster = RasterRenderer::settings_for(config);

  CloseSettings close;
  close.enabled = !o.no_close;
  SelectionRecord record;
  SelectionResult result;
  std::string seed_rule;
  std::optional<std::size_t> clicked_view;
  float grow = o.grow.value_or(0.0f);

  if (o.labels) {
    record.method = "labels";
    record.parameters["threshold"] = o.threshold;
    LabelSelectSettings ls;
    ls.threshold = o.threshold;
    ls.close = close;
    result = select_by_label(pts, ls);
    seed_rule = "by label > " + num(o.threshold);
    // Labels no mask pixel constrains stay near their initial 0.5 until training has run long enough: a
    // seed set dominated by such uncertain labels is worth a warning.
    std::size_t confident = 0, uncertain = 0;
    for (float l : pts.label) {
      confident += l > 0.5f;
      uncertain += l > o.threshold && l <= 0.5f;
    }
    std::printf("labels: %zu above 0.5, %zu in (%s, 0.5]\n", confident, uncertain, num(o.threshold).c_str());
    if (uncertain > confident && o.threshold < 0.5f)
      std::printf("warning: most selected labels are barely above the threshold (not yet learned?): train longer, "
                  "or try --threshold 0.5 or --masks\n");
    if (result.summary.seeds == 0) {
      const float max_label = pts.label.empty() ? 0.0f : *std::max_element(pts.label.begin(), pts.label.end());
      throw Error(run_dir.string(), "no Gaussian has a label above " + num(o.threshold) +
                                        " (the largest is " + num(max_label) +
                                        "): the run's labels were not learned from object masks, or the threshold "
                                        "is too high - lower --threshold, or select with --masks or --click");
    }
  } else if (o.masks) {
    record.method = "masks";
    std::optional<fs::path> dir;
    if (!o.masks_dir.empty()) dir = fs::absolute(o.masks_dir);
    const std::vector<MaskedView> views = load_masked_views(ds.train, dir);
    std::printf("voting with the object masks of %zu training views%s\n", views.size(),
                dir ? (" from " + dir->string()).c_str() : "");
    MaskVoteSettings ms;
    ms.min_fraction = o.min_fraction;
    const MaskVotes votes = labels_from_masks(model, views, ms, raster, [](std::size_t done, std::size_t total) {
      if (done % 10 == 0 || done == total) std::printf("  voted in %zu / %zu views\n", done, total);
    });
    record.parameters["mask_dir"] = dir ? dir->string() : std::string();
    record.parameters["views"] = views.size();
    record.parameters["min_fraction"] = o.min_fraction;
    std::size_t ever_visible = 0;
    for (auto v : votes.visible) ever_visible += v > 0;
    result = close_selection(pts, votes.selected, close);
    seed_rule = "by mask votes";
    if (result.summary.seeds == 0)
      throw Error(dir ? dir->string() : config.data,
                  "no Gaussian falls inside the object masks in at least " + percent(o.min_fraction) +
                      " of the views where it is visible (" + std::to_string(ever_visible) +
                      " Gaussians are visible at all): are the masks white on the object? Lower --min-fraction, "
                      "or use --click");
  } else {
    record.method = "click";
    const std::size_t vi = find_view(ds.train, o.click[0]);
    const View& view = ds.train[vi];
    const int x = parse_int(o.click[1], "X"), y = parse_int(o.click[2], "Y");
    if (x < 0 || y < 0 || x >= view.camera.width || y >= view.camera.height)
      throw Error("--click", "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside view " +
                                 view.name + " (" + std::to_string(view.camera.width) + "x" +
                                 std::to_string(view.camera.height) + " at the run's training resolution)");
    const PickResult p = pick_gaussian(model, view.camera, x, y);
    if (!p.hit)
      throw Error("--click", "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") of view " + view.name +
                                 " shows background (the ray's opacity is " + num(p.ray_alpha) +
                                 "): click on the object");
    std::printf("picked Gaussian %u in %s at (%d, %d): weight %.3f, depth %.3f, point (%.3f, %.3f, %.3f)\n", p.gaussian,
                view.name.c_str(), x, y, p.weight, p.depth, p.point.x, p.point.y, p.point.z);
    clicked_view = vi;
    record.parameters["view"] = view.name;
    record.parameters["x"] = x;
    record.parameters["y"] = y;
    record.parameters["picked"] = p.gaussian;
    record.parameters["pick_weight"] = p.weight;
    record.parameters["pick_depth"] = p.depth;
    SelectionMask seeds(model.count(), 0);
    seeds[p.gaussian] = 1;
    // A click selects one Gaussian: growing is what makes it the object, so it grows by default.
    if (!o.grow) grow = 0.5f;
    result.mask = seeds;
    result.summary.total = model.count();
    result.summary.seeds = result.summary.selected = 1;
    seed_rule = "picked";
  }

  nlohmann::json grow_json;
  if (grow > 0.0f) {
    GrowSettings gs;
    gs.grow = grow;
    gs.max_fraction = o.max_fraction;
    const SelectionGraph graph = build_selection_graph(pts);
    const GrowResult g = grow_selection(pts, graph, result.mask, gs);
    grow_json = {{"grow", grow}, {"seeds", g.seeds}, {"added", g.added}};
    std::printf("grew by %zu Gaussians (grow %.2f)\n", g.added, grow);
    if (g.hit_limit)
      throw Error(run_dir.string(), "growing the selection would take more than " + percent(o.max_fraction) +
                                        " of the scene's Gaussians (stopped at " + std::to_string(g.seeds + g.added) +
                                        "): it leaks into the surroundings - lower --grow (now " +
                                        num(grow) + ") or raise --max-fraction");
    result.mask = g.mask;
    result.summary.selected = count_selected(g.mask);
  }
  // A click's object is what growing found: that region is closed like the other rules' seeds. Without
  // growth the user asked for exactly the picked Gaussian.
  if (record.method == "click" && grow > 0.0f) {
    result = close_selection(pts, result.mask, close);
    seed_rule = "picked and grown";
  }
  record.parameters["grow"] = grow;
  record.parameters["close"] = close.enabled && (record.method != "click" || grow > 0.0f);
  record.parameters["max_fraction"] = o.max_fraction;
  const SelectionSummary& s = result.summary;
  std::printf("selected %s\n", s.describe(seed_rule).c_str());

  if (s.selected == 0) throw Error(run_dir.string(), "the selection is empty: nothing to remove");
  if (s.fraction() > o.max_fraction) {
    std::string hint = record.method == "labels"   ? "raise --threshold (now " + num(o.threshold) + ")"
                       : record.method == "masks" ? "raise --min-fraction (now " + num(o.min_fraction) + ")"
                                                  : "lower --grow";
    if (s.by_volume > s.seeds) hint += ", or add --no-close (the hull added " + std::to_string(s.by_volume) + ")";
    throw Error(run_dir.string(), "the selection holds " + percent(s.fraction()) + " of the scene's Gaussians, more than " +
                                      "--max-fraction " + percent(o.max_fraction) +
                                      ": that is not one object - " + hint + ", or raise --max-fraction if it really is");
  }

  record.summary = summary_json(s);
  if (!grow_json.is_null()) record.summary["grow"] = grow_json;
  std::error_code ec;
  const fs::path rel = fs::relative(source, run_dir, ec);
  record.model_source = !ec && !rel.empty() && rel.native()[0] != '.' ? rel.string() : source;
  record.model_fingerprint = model_fingerprint(model);
  write_selection(json_path, record, result.mask);
  std::printf("wrote %s and %s\n", json_path.string().c_str(),
              (json_path.parent_path() / (json_path.stem().string() + ".npy")).string().c_str());

  const fs::path preview_dir = json_path.parent_path() / (json_path.stem().string() + "_preview");
  const std::vector<std::size_t> pv = preview_views(ds.train.size(), o.previews, clicked_view);
  if (!pv.empty()) fs::create_directories(preview_dir);
  for (std::size_t vi : pv) {
    const View& v = ds.train[vi];
    save_png(preview_dir / (v.name + ".png"), render_selection_preview(model, result.mask, v.camera, raster));
  }
  if (!pv.empty())
    std::printf("previews (tinted | removed) of %zu views in %s\n", pv.size(), preview_dir.string().c_str());
  std::printf("done in %.1f s\n", seconds_since(t0));
}

void setup_select(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("select", "Choose the object to remove: by learned label, object masks or a click");
  c->add_option("run", o->run, "Run folder written by `goris train`")->required();
  auto* click = c->add_option("--click", o->click,
                              "VIEW X Y: the Gaussian shown at pixel (X, Y) of training view VIEW (name like r_012 or "
                              "index), grown over similar neighbours (--grow, default 0.5)")
                    ->expected(3);
  auto* masks = c->add_option("--masks", o->masks_dir,
                              "[DIR] Vote with object masks: the data set's train mask_XXX.png, or DIR/mask_XXX.png "
                              "or DIR/<view name>.png when DIR is given (after RUN)")
                    ->expected(0, 1);
  auto* labels = c->add_flag("--labels", o->labels, "Gaussians whose learned label exceeds --threshold");
  c->add_option("--threshold", o->threshold, "Label threshold for --labels (paper: 0.3)")->check(CLI::Range(0.0, 0.999));
  c->add_option("--min-fraction", o->min_fraction,
                "--masks: inside the mask in at least this fraction of the views where the Gaussian is visible")
      ->check(CLI::Range(0.01, 1.0));
  c->add_option("--grow", o->grow, "Grow the selection over similar neighbouring Gaussians, 0 (off) .. 1")
      ->check(CLI::Range(0.0, 1.0));
  c->add_option("--max-fraction", o->max_fraction, "Refuse selections larger than this fraction of all Gaussians")
      ->check(CLI::Range(0.001, 1.0));
  c->add_flag("--no-close", o->no_close, "Do not add the Gaussians inside the hull of the selected centres");
  c->add_option("--out", o->out, "Selection file to write (default RUN/selection.json; the mask goes beside it)");
  c->add_option("--previews", o->previews, "Preview images of training views to write")->check(cli::whole(0, 1000));
  c->add_option("--device", o->device, "auto | cpu | cuda (rendering for masks and previews)")
      ->check(CLI::IsMember({"auto", "cpu", "cuda"}));
  c->callback([o, click, masks, labels] {
    o->masks = masks->count() > 0;
    run_select(*o, int(click->count() > 0) + int(o->masks) + int(labels->count() > 0));
  });
}

}  // namespace
GORIS_COMMAND(30, setup_select);
