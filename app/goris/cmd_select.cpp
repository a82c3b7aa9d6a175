// `goris select RUN [--click VIEW X Y ... | --masks [DIR] | --labels [--threshold T]] [regions] [edits]
// [--out FILE] [--write-masks DIR]`: chooses the target of object removal and stores it in the run folder
// (selection.json + selection.npy, removal/selection/selection_file.h) with preview images (tinted | removed) of
// a few training views.
//
//   --labels  Gaussians with learned label > T (0.3), closed by the hull of their centres (paper Sec. 3.3)
//   --masks   depth-tested votes of the Gaussian centres in the training views' object masks, then closed
//   --click   a pixel of a training view: by default its region of that view (render depth and photo colour,
//             selection_click_region.h), lifted by the Gaussians' rendered weight in the clicked views,
//             closed, voted again by every view, closed;
//             with --click-by grow (or --grow) the Gaussian it shows, grown over similar neighbours, then
//             closed; repeated grown clicks are united, or intersected with --clicks intersect
// Regions (each repeatable, united with one another): --rect / --polygon in a training view's pixels
// (--through visible: only what that view shows; all: every centre inside), --sphere, --box, --colour.
// With a rule above they are combined with its result by --combine (union, subtract, intersect).
// Then --dilate / --shrink graph steps and --invert. --write-masks renders the selection's object masks
// for every training view (selection_view_masks.h) and, with --masks-iou, scores them against the data
// set's own masks.
// An empty selection, or one larger than --max-fraction of the scene, is an error that says what to change.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "core/io/dataset.h"
#include "core/inpaint/mask.h"
#include "core/io/image.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "train/run/run_output_guard.h"
#include "core/util/error.h"
#include "removal/selection/selection.h"
#include "removal/selection/selection_click_flow.h"
#include "train/setup/auto_mode.h"
#include "train/radiance/raster_renderer.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, out, device = "auto", data;
  std::vector<std::string> click;  // VIEW X Y, repeated
  std::string clicks = "union";
  std::string click_by;  // region | grow; empty: region, or grow when --grow is given
  std::string masks_dir;
  bool masks = false, labels = false, no_close = false, invert = false;
  std::vector<std::string> rects, polygons;  // VIEW COORDS pairs
  std::vector<std::string> spheres, boxes, colours;
  std::string through = "visible", combine = "union";
  int dilate = 0, shrink = 0;
  std::string write_masks, masks_iou;
  bool masks_iou_given = false;
  float threshold = 0.3f, min_fraction = MaskVoteSettings{}.min_fraction, max_fraction = 0.5f;
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
std::size_t find_view(const std::vector<View>& views, const std::string& key, const std::string& what = "--click") {
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
  throw Error(what, "no training view '" + key + "' (give a name such as " + views.front().name +
                             " or an index 0.." + std::to_string(views.size() - 1) + ")");
}

// "a,b,c,..." with a count from `counts`; `what` names the argument in errors.
std::vector<float> parse_numbers(const std::string& text, const std::string& what, std::vector<std::size_t> counts) {
  const std::vector<float> v = parse_number_list(text, what);
  if (std::find(counts.begin(), counts.end(), v.size()) == counts.end()) {
    std::string want;
    for (std::size_t c : counts) want += (want.empty() ? "" : " or ") + std::to_string(c);
    throw Error(what, "'" + text + "' has " + std::to_string(v.size()) + " numbers, expected " + want);
  }
  return v;
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

// Every training view's object mask from the selection, DIR/mask_XXX.png; with --masks-iou scored against
// the data set's (or DIR's) masks into DIR/iou.json.
void write_view_masks(const Options& o, const Dataset& ds, const GaussianModel& model, const SelectionMask& sel,
                      const RasterSettings& raster, const OutputGuard& guard) {
  const fs::path dir = fs::absolute(o.write_masks);
  std::vector<MaskedView> exact;
  if (o.masks_iou_given) {
    std::optional<fs::path> against;
    if (!o.masks_iou.empty()) against = fs::absolute(o.masks_iou);
    if (against && fs::equivalent(*against, dir))
      throw Error("--masks-iou", against->string() + " is the --write-masks folder itself");
    exact = load_masked_views(ds.train, against);
  }
  fs::create_directories(dir);
  nlohmann::json per_view = nlohmann::json::array();
  double sum = 0.0, worst = 1.0;
  std::size_t scored = 0;
  const SelectionViewMasks masks = selection_view_masks(model, sel, cameras_of(ds.train), raster);
  if (masks.lowered)
    std::fprintf(stderr,
                 "goris select: the selection covers no pixel of any view by more than half (its largest coverage is "
                 "%.2f): the masks are cut at %.2f instead\n",
                 masks.peak, masks.threshold);
  else if (!(masks.peak > 0.0f))
    std::fprintf(stderr, "goris select: the selection covers no pixel of any training view: every mask is empty\n");
  for (std::size_t k = 0; k < ds.train.size(); ++k) {
    const View& v = ds.train[k];
    const Mask& m = masks.masks[k];
    const fs::path file = dir / object_mask_file_name(v.name);
    check_output_file(file, guard);
    save_mask_png(file, m);
    auto it = std::find_if(exact.begin(), exact.end(), [&](const MaskedView& e) { return e.name == v.name; });
    if (it == exact.end()) continue;
    const double iou = mask_iou(m, mask_from_image(it->mask));
    per_view.push_back({{"view", v.name}, {"iou", iou}, {"pixels", count_set(m)}});
    sum += iou;
    worst = std::min(worst, iou);
    ++scored;
  }
  std::printf("wrote %zu object masks to %s\n", ds.train.size(), dir.string().c_str());
  if (!o.masks_iou_given) return;
  if (scored == 0) throw Error("--masks-iou", "no training view has an exact mask to compare with");
  const double mean = sum / double(scored);
  const nlohmann::json j = {{"views", scored}, {"mean_iou", mean}, {"min_iou", worst}, {"per_view", per_view}};
  const fs::path out = dir / "iou.json", tmp = dir / "iou.json.tmp";
  {
    std::FILE* f = std::fopen(tmp.string().c_str(), "w");
    if (!f) throw Error(tmp.string(), "cannot write");
    const std::string text = j.dump(1) + "\n";
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) throw Error(tmp.string(), "write failed");
  }
  fs::rename(tmp, out);
  std::printf("masks IoU against the exact masks: mean %.4f, min %.4f over %zu views (%s)\n", mean, worst, scored,
              out.string().c_str());
}

void run_select(const Options& o, int n_methods) {
  const bool regions = !o.rects.empty() || !o.polygons.empty() || !o.spheres.empty() || !o.boxes.empty() ||
                       !o.colours.empty();
  if (n_methods > 1 || (n_methods == 0 && !regions))
    throw Error("goris select: choose one of --click VIEW X Y, --masks [DIR], --labels, and/or regions (--rect, "
                "--polygon, --sphere, --box, --colour)");
  const Through through = through_from_name(o.through);
  const Combine combine = combine_from_name(o.combine);
  const Combine clicks_combine = combine_from_name(o.clicks);
  if (clicks_combine == Combine::Subtract) throw Error("--clicks", "is union or intersect");
  if (!o.masks_iou_given ? false : o.write_masks.empty())
    throw Error("--masks-iou", "needs --write-masks DIR (the masks it scores)");
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path run_dir = fs::absolute(o.run);
  const TrainConfig config = read_run_config_with_data(run_dir, o.data);
  // Never into the data set or over the run's other files (the selection itself is this command's output).
  const fs::path json_path = o.out.empty() ? selection_json_path(run_dir) : fs::absolute(o.out);
  const OutputGuard guard = run_output_guard(run_dir, config, /*keep_selection=*/false);
  check_output_file(json_path, guard);
  check_output_file(json_path.parent_path() / (json_path.stem().string() + ".npy"), guard);
  const Device device = resolve_device(o.device);
  const Dataset ds = load_dataset(config.input.data, dataset_options(config));
  if (ds.train.empty()) throw Error(config.input.data, "the data set has no training views");
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
  std::vector<SelectionMask> clicked_seeds;  // one per click, grown apart
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
      throw Error(dir ? dir->string() : config.input.data,
                  "no Gaussian falls inside the object masks in at least " + percent(o.min_fraction) +
                      " of the views where it is visible (" + std::to_string(ever_visible) +
                      " Gaussians are visible at all): are the masks white on the object? Lower --min-fraction, "
                      "or use --click");
  } else if (!o.click.empty()) {
    record.method = "click";
    nlohmann::json clicks = nlohmann::json::array();
    std::vector<SelectionMask> picked;
    const bool by_region = o.click_by.empty() ? !o.grow.has_value() : o.click_by == "region";
    if (by_region && o.grow && *o.grow > 0.0f)
      throw Error("--grow", "grows a click over similar Gaussians (--click-by grow); --click-by region takes the "
                            "clicked views' regions instead");
    std::vector<ClickView> regions_2d;
    // The glossy masks the run trained with: the surface the target stands on, whose far side holds its
    // reflection and whose pixels are never the target. They help and are not needed: a run whose detected
    // masks are gone selects without them, and says so.
    std::vector<std::vector<float>> gloss_store(ds.train.size());
    if (by_region) try {
        gloss_store = run_glossy_masks(config, ds.train);
      } catch (const Error& e) {
        std::fprintf(stderr, "warning: selecting without the run's glossy masks: %s\n", e.what());
      }
    const std::vector<const std::vector<float>*> gloss = glossy_mask_pointers(gloss_store);
    for (std::size_t c = 0; c + 2 < o.click.size(); c += 3) {
      const std::size_t vi = find_view(ds.train, o.click[c]);
      const View& view = ds.train[vi];
      const int x = parse_int(o.click[c + 1], "X"), y = parse_int(o.click[c + 2], "Y");
      ClickOutcome click;
      if (by_region) {
        const Image photo = load_view_image(view, dataset_options(config), Device::CPU);
        click = click_in_view(model, view, photo, x, y, raster, true, gloss[vi]);
      } else {
        click = click_in_view(model, view, Image(), x, y, raster, /*region=*/false);
      }
      const PickResult& p = click.pick;
      std::printf("picked Gaussian %u in %s at (%d, %d): weight %.3f, depth %.3f, point (%.3f, %.3f, %.3f)\n",
                  p.gaussian, view.name.c_str(), x, y, p.weight, p.depth, p.point.x, p.point.y, p.point.z);
      if (!clicked_view) clicked_view = vi;
      clicks.push_back({{"view", view.name}, {"x", x}, {"y", y}, {"picked", p.gaussian}, {"pick_weight", p.weight},
                        {"pick_depth", p.depth}});
      if (by_region) {
        const ClickRegion& cr = click.region;
        std::printf("  region of the click in %s: %zu pixels (%s of the view), colour tolerance %.2f%s\n",
                    view.name.c_str(), cr.area,
                    percent(double(cr.area) / double(view.camera.width * view.camera.height)).c_str(), cr.tolerance,
                    cr.leaked_at_first ? " (leaks even at the lowest tolerance)" : "");
        clicks.back()["region_pixels"] = cr.area;
        clicks.back()["region_tolerance"] = cr.tolerance;
        regions_2d.push_back({view.name, view.camera, cr.mask});
      }
      SelectionMask seeds(model.count(), 0);
      seeds[p.gaussian] = 1;
      picked.push_back(std::move(seeds));
    }
    // One click keeps the flat record it always had; more clicks are listed.
    if (clicks.size() == 1)
      for (auto it = clicks[0].begin(); it != clicks[0].end(); ++it) record.parameters[it.key()] = it.value();
    else {
      record.parameters["clicks"] = clicks;
      record.parameters["combine_clicks"] = o.clicks;
    }
    if (by_region) {
      // The clicked views' regions take the Gaussians that draw their pixels (by rendered weight, in every
      // clicked view that shows the Gaussian), then the hull adds the object's interior, and every view's
      // silhouette of the selection votes once more (it adds the side no clicked view saw).
      record.parameters["click_by"] = "region";
      const ClickSelection cs = select_by_click_regions(model, pts, regions_2d, ds.train, raster, close, gloss);
      result = cs.result;
      if (cs.support.found) {
        record.parameters["glossy_surface"] = {{"normal", {cs.support.normal.x, cs.support.normal.y, cs.support.normal.z}},
                                               {"offset", cs.support.offset},
                                               {"left_out_beyond", cs.beyond_support}};
        std::printf("  the glossy surface it stands on: normal (%.3f, %.3f, %.3f), %zu Gaussians beyond it left out "
                    "(the target's reflection)\n",
                    cs.support.normal.x, cs.support.normal.y, cs.support.normal.z, cs.beyond_support);
      }
      if (cs.revoted)
        std::printf("  %zu Gaussians from the clicked views, %zu after every training view's vote\n",
                    cs.from_clicked_views, result.summary.selected);
      seed_rule = "in the clicked views' regions";
      if (result.summary.seeds == 0)
        throw Error("--click", "no Gaussian lies inside the clicked region of every clicked view that sees it: "
                               "are the clicks on the same object?");
      const fs::path json_dir = json_path.parent_path() / (json_path.stem().string() + "_preview");
      fs::create_directories(json_dir);
      for (const ClickView& v : regions_2d) save_mask_png(json_dir / ("click_region_" + v.name + ".png"), v.region);
    } else {
      // A click selects one Gaussian: growing is what makes it the object, so it grows by default.
      record.parameters["click_by"] = "grow";
      if (!o.grow) grow = 0.5f;
      clicked_seeds = std::move(picked);
      result.summary.total = model.count();
      result.summary.seeds = clicked_seeds.size();
      seed_rule = "picked";
    }
  }

  nlohmann::json grow_json;
  std::optional<SelectionGraph> graph;  // built once, for growing and the graph steps
  auto the_graph = [&]() -> const SelectionGraph& {
    if (!graph) graph = build_selection_graph(pts);
    return *graph;
  };
  auto grow_one = [&](const SelectionMask& seeds) {
    GrowSettings gs;
    gs.grow = grow;
    gs.max_fraction = o.max_fraction;
    const GrowResult g = grow_selection(pts, the_graph(), seeds, gs);
    std::printf("grew by %zu Gaussians (grow %.2f)\n", g.added, grow);
    if (g.hit_limit)
      throw Error(run_dir.string(), "growing the selection would take more than " + percent(o.max_fraction) +
                                        " of the scene's Gaussians (stopped at " + std::to_string(g.seeds + g.added) +
                                        "): it leaks into the surroundings - lower --grow (now " +
                                        num(grow) + ") or raise --max-fraction");
    return g;
  };
  if (!clicked_seeds.empty()) {
    // Each click is grown from its own Gaussian (its own reference colour), then the views' evidence is
    // united or intersected.
    SelectionMask merged;
    std::size_t added = 0;
    for (const SelectionMask& seeds : clicked_seeds) {
      SelectionMask m = seeds;
      if (grow > 0.0f) {
        const GrowResult g = grow_one(seeds);
        added += g.added;
        m = g.mask;
      }
      merged = merged.empty() ? m : combine_selections(merged, m, clicks_combine);
    }
    if (grow > 0.0f) grow_json = {{"grow", grow}, {"seeds", clicked_seeds.size()}, {"added", added}};
    result.mask = merged;
    result.summary.selected = count_selected(merged);
  } else if (grow > 0.0f && !result.mask.empty()) {
    const GrowResult g = grow_one(result.mask);
    grow_json = {{"grow", grow}, {"seeds", g.seeds}, {"added", g.added}};
    result.mask = g.mask;
    result.summary.selected = count_selected(g.mask);
  }
  // A click's object is what growing found: that region is closed like the other rules' seeds. Without
  // growth the user asked for exactly the picked Gaussians.
  if (record.method == "click" && grow > 0.0f) {
    result = close_selection(pts, result.mask, close);
    seed_rule = "picked and grown";
  }

  // Regions: united with one another, then combined with the rule's result.
  if (regions) {
    SelectionMask region(model.count(), 0);
    nlohmann::json rj = nlohmann::json::array();
    auto add = [&](const SelectionMask& m, nlohmann::json what) {
      what["selected"] = count_selected(m);
      rj.push_back(what);
      region = combine_selections(region, m, Combine::Union);
    };
    auto screen = [&](const std::vector<std::string>& args, const char* flag, bool rect) {
      for (std::size_t k = 0; k + 1 < args.size(); k += 2) {
        const View& v = ds.train[find_view(ds.train, args[k], flag)];
        ScreenPolygon poly;
        if (rect) {
          const std::vector<float> c = parse_numbers(args[k + 1], flag, {4});
          poly = rect_polygon({c[0], c[1]}, {c[2], c[3]});
        } else {
          poly = parse_polygon(args[k + 1], flag);
        }
        add(select_in_view_region(model, pts, v.camera, poly, through, raster),
            {{"kind", rect ? "rect" : "polygon"}, {"view", v.name}, {"points", args[k + 1]},
             {"through", through_name(through)}});
      }
    };
    screen(o.rects, "--rect", true);
    screen(o.polygons, "--polygon", false);
    for (const std::string& t : o.spheres) {
      const std::vector<float> c = parse_numbers(t, "--sphere", {4});
      if (c[3] < 0.0f) throw Error("--sphere", "radius " + num(c[3]) + " is negative");
      add(select_sphere(pts, {c[0], c[1], c[2]}, c[3]), {{"kind", "sphere"}, {"values", t}});
    }
    for (const std::string& t : o.boxes) {
      const std::vector<float> c = parse_numbers(t, "--box", {6, 9});
      SelectionBox box;
      box.centre = {c[0], c[1], c[2]};
      box.half_extent = {c[3], c[4], c[5]};
      if (c[3] < 0.0f || c[4] < 0.0f || c[5] < 0.0f) throw Error("--box", "half extents must not be negative");
      if (c.size() == 9) box.rotation = rotation_from_euler_degrees({c[6], c[7], c[8]});
      add(select_box(pts, box), {{"kind", "box"}, {"values", t}});
    }
    for (const std::string& t : o.colours) {
      const std::vector<float> c = parse_numbers(t, "--colour", {4});
      if (c[3] < 0.0f) throw Error("--colour", "distance " + num(c[3]) + " is negative");
      add(select_by_colour(pts, {c[0], c[1], c[2]}, c[3]), {{"kind", "colour"}, {"values", t}});
    }
    record.parameters["regions"] = rj;
    if (n_methods == 0) {
      record.method = "region";
      result.mask = region;
      result.summary.total = model.count();
      result.summary.seeds = count_selected(region);
      seed_rule = "in the regions";
    } else {
      record.parameters["combine"] = o.combine;
      result.mask = combine_selections(result.mask, region, combine);
      seed_rule += std::string(", ") + combine_name(combine) + " regions";
    }
    std::printf("regions select %zu Gaussians\n", count_selected(region));
  }
  if (o.dilate > 0) result.mask = dilate_selection(the_graph(), result.mask, o.dilate);
  if (o.shrink > 0) result.mask = shrink_selection(the_graph(), result.mask, o.shrink);
  if (o.invert) result.mask = invert_selection(result.mask);
  if (o.dilate > 0 || o.shrink > 0 || o.invert || regions) {
    record.parameters["dilate"] = o.dilate;
    record.parameters["shrink"] = o.shrink;
    record.parameters["invert"] = o.invert;
    result.summary.selected = count_selected(result.mask);
    if (o.invert) seed_rule += ", inverted";
  }
  record.parameters["grow"] = grow;
  record.parameters["close"] =
      close.enabled && (record.method != "click" || grow > 0.0f || record.parameters.value("click_by", "") == "region");
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
  if (!o.write_masks.empty()) write_view_masks(o, ds, model, result.mask, raster, guard);
  std::printf("done in %.1f s\n", seconds_since(t0));
}

void setup_select(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("select", "Choose the object to remove: by learned label, object masks or a click");
  c->add_option("run", o->run, "Run folder written by `goris train`")->required();
  auto* click = c->add_option("--click", o->click,
                              "VIEW X Y: the Gaussian shown at pixel (X, Y) of training view VIEW (name like r_012 or "
                              "index), grown over similar neighbours (--grow, default 0.5); repeat for more views")
                    ->expected(3)
                    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--click-by", o->click_by,
                "region | grow: a click selects its region of the clicked view (depth and colour edges of the "
                "render and photo), lifted by the Gaussians' rendered weight in the clicked views (default), or the picked Gaussian grown over "
                "similar neighbours (default when --grow is given)")
      ->check(CLI::IsMember({"region", "grow"}));
  c->add_option("--clicks", o->clicks, "union | intersect: how several clicks' grown selections combine")
      ->check(CLI::IsMember({"union", "intersect"}));
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
  c->add_option("--rect", o->rects,
                "VIEW x0,y0,x1,y1: centres inside this rectangle of training view VIEW's pixels (repeatable)")
      ->expected(2)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--polygon", o->polygons, "VIEW x,y,x,y,...: centres inside this polygon (lasso) of view VIEW (repeatable)")
      ->expected(2)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--through", o->through,
                "visible: --rect / --polygon take only what the view shows (depth-tested centres); all: every "
                "centre inside")
      ->check(CLI::IsMember({"visible", "all"}));
  c->add_option("--sphere", o->spheres, "cx,cy,cz,r: centres inside this sphere (world units; repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--box", o->boxes,
                "cx,cy,cz,hx,hy,hz[,rx,ry,rz]: centres inside this box (half extents; rotation in degrees about "
                "x, then y, then z; repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--colour", o->colours, "r,g,b,d: Gaussians whose base (SH DC) colour lies within d of r,g,b (0..1)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--combine", o->combine,
                "union | subtract | intersect: how the regions combine with --click / --masks / --labels")
      ->check(CLI::IsMember({"union", "subtract", "intersect"}));
  c->add_option("--dilate", o->dilate, "Add this many rings of graph neighbours to the selection")
      ->check(cli::whole(0, 100));
  c->add_option("--shrink", o->shrink, "Remove this many rings from the selection's border")->check(cli::whole(0, 100));
  c->add_flag("--invert", o->invert, "Select everything else (last step; raise --max-fraction as needed)");
  c->add_option("--write-masks", o->write_masks,
                "DIR: write every training view's object mask of the selection (mask_XXX.png, depth-tested coverage)");
  auto* iou = c->add_option("--masks-iou", o->masks_iou,
                            "[DIR] with --write-masks: score them (IoU) against the data set's object masks, or "
                            "DIR's; writes iou.json beside them")
                  ->expected(0, 1);
  c->add_flag("--no-close", o->no_close, "Do not add the Gaussians inside the hull of the selected centres");
  c->add_option("--out", o->out, "Selection file to write (default RUN/selection.json; the mask goes beside it)");
  c->add_option("--previews", o->previews, "Preview images of training views to write")->check(cli::whole(0, 1000));
  cli::add_device_option(*c, o->device, "rendering for masks and previews");
  cli::add_data_option(*c, o->data);
  c->callback([o, click, masks, labels, iou] {
    o->masks = masks->count() > 0;
    o->masks_iou_given = iou->count() > 0;
    run_select(*o, int(click->count() > 0) + int(o->masks) + int(labels->count() > 0));
  });
}

}  // namespace
GORIS_COMMAND(30, setup_select);
