// `goris demo`: the main job on the embedded default scene (resources/default_scene), end to end on the
// chosen device: train a short schedule, render the test views with every map, evaluate against the views
// with the target (`--gt full`), select the target from its masks, remove it (stage 2), evaluate the cleaned
// scene against the views without it, and write report.md with side-by-side images a person can look at.
// Each step runs as its own `goris` subcommand in a child process (the same binary), so the demo exercises
// exactly what a user types and a failing step stops the demo with that step's message.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/cli_common/command.h"
#include "app/cli_common/json_number.h"
#include "app/cli_common/number_checks.h"
#include "core/io/dataset.h"
#include "core/io/file_bytes.h"
#include "core/metrics/removal_metrics.h"
#include "core/util/error.h"
#include "removal/pipeline/removal_pipeline.h"
#include "train/config/train_config.h"

extern char** environ;

namespace {
namespace fs = std::filesystem;
using goris::Error;

struct Options {
  std::string data = std::string(GORIS_RESOURCE_DIR) + "/default_scene";
  std::string out = "goris-demo";
  std::string device = "auto";
  int iters = 2000;
  std::string mode = "auto";
  int report_views = 4;
};

fs::path self_executable() { return fs::read_symlink("/proc/self/exe"); }

// Runs `goris ARGS` as a child process; returns its wall seconds.
double run_step(const std::string& title, std::vector<std::string> args) {
  const auto start = std::chrono::steady_clock::now();
  std::printf("\n== demo: %s\n$ goris", title.c_str());
  for (auto& a : args) std::printf(" %s", a.c_str());
  std::printf("\n");
  std::fflush(stdout);
  const std::string exe = self_executable().string();
  args.insert(args.begin(), exe);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw Error(exe, "could not start the demo step '" + title + "'");
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error("demo step '" + title + "' failed (see its message above)");
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Wall time of each demo step, for the report.
using StepTimes = std::vector<std::pair<std::string, double>>;

// Labelled images side by side, at the first one's size. A part with `optional` set that does not exist
// is a black tile saying so (e.g. no lighting-aware mask on a radiance run).
struct Tile {
  fs::path path;
  std::string label;
  bool optional = false;
};
cv::Mat tile_row(const std::vector<Tile>& parts) {
  std::vector<cv::Mat> tiles;
  for (const auto& [path, label, optional] : parts) {
    cv::Mat img = optional && !fs::exists(path) ? cv::Mat() : cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (img.empty() && optional && !tiles.empty()) {
      tiles.push_back(cv::Mat::zeros(tiles[0].size(), CV_8UC3));
      cv::putText(tiles.back(), label + ": none", {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {255, 255, 255}, 1, cv::LINE_AA);
      continue;
    }
    if (img.empty()) throw Error(path.string(), "missing or unreadable image for the demo report");
    if (img.depth() != CV_8U) img.convertTo(img, CV_8U, 1.0 / 257.0);
    if (img.channels() == 4) {  // composite on black, as training does
      cv::Mat bgr, alpha;
      cv::cvtColor(img, bgr, cv::COLOR_BGRA2BGR);
      cv::extractChannel(img, alpha, 3);
      cv::cvtColor(alpha, alpha, cv::COLOR_GRAY2BGR);
      cv::multiply(bgr, alpha, img, 1.0 / 255.0);
    } else if (img.channels() == 1) {
      cv::cvtColor(img, img, cv::COLOR_GRAY2BGR);
    }
    if (!tiles.empty() && img.size() != tiles[0].size()) cv::resize(img, img, tiles[0].size());
    cv::putText(img, label, {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {255, 255, 255}, 1, cv::LINE_AA);
    tiles.push_back(img);
  }
  cv::Mat row;
  cv::hconcat(tiles, row);
  return row;
}

// Where the removal had to change the image (full_ and r_ differ, core/metrics/removal_metrics.h), cropped
// to the region's bounding box with a margin and enlarged: with the target | ground truth without it | render
// after removal. Empty when the view has no full_ image or nothing changed.
cv::Mat region_crop_row(const goris::View& v, const fs::path& render, int scale = 3) {
  if (!v.full_image || !fs::exists(render)) return {};
  cv::Mat before = cv::imread(v.full_image->string(), cv::IMREAD_COLOR), after = cv::imread(v.image.string(), cv::IMREAD_COLOR);
  cv::Mat ours = cv::imread(render.string(), cv::IMREAD_COLOR);
  if (before.empty() || after.empty() || ours.empty() || before.size() != after.size() || ours.size() != after.size())
    return {};
  const int w = after.cols, h = after.rows;
  auto planar = [&](const cv::Mat& m) {
    std::vector<float> p(std::size_t(3) * w * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) p[(std::size_t(c) * h + y) * w + x] = m.at<cv::Vec3b>(y, x)[2 - c] / 255.0f;
    return p;
  };
  const goris::ChangedRegion region = goris::changed_region(planar(before).data(), planar(after).data(), w, h);
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (region.mask[std::size_t(y) * w + x]) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  if (x1 < 0) return {};
  const int m = std::max(4, (x1 - x0) / 8);
  const int rx = std::max(0, x0 - m), ry = std::max(0, y0 - m);
  const cv::Rect roi(rx, ry, std::min(w, x1 + m + 1) - rx, std::min(h, y1 + m + 1) - ry);
  std::vector<cv::Mat> tiles;
  for (const auto& [img, label] : {std::pair{before, "with the target"}, {after, "truth without it"}, {ours, "after removal"}}) {
    cv::Mat t;
    cv::resize(img(roi), t, {}, scale, scale, cv::INTER_NEAREST);
    cv::putText(t, label, {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {255, 255, 255}, 1, cv::LINE_AA);
    tiles.push_back(t);
  }
  cv::Mat row;
  cv::hconcat(tiles, row);
  return row;
}

// A row: ground truth | render | depth | normal.
cv::Mat comparison_row(const fs::path& gt, const fs::path& renders, const std::string& name) {
  return tile_row({{gt, "ground truth"},
                   {renders / (name + ".png"), "render"},
                   {renders / (name + "_depth.png"), "depth"},
                   {renders / (name + "_normal.png"), "normal"}});
}

void write_png(const fs::path& path, const cv::Mat& img) {
  std::vector<unsigned char> png;
  cv::imencode(".png", img, png);
  goris::write_file_bytes(path, png.data(), png.size());
}

// What stage 2 made for each reference view: the photo | lighting-aware mask | the target's shadow |
// inpainting mask | inpainted colour.
std::string stage2_rows(const goris::Dataset& ds, const fs::path& removed, const fs::path& out) {
  std::ifstream rf(removed / "reference.json");
  if (!rf) return "";
  const nlohmann::json refs = nlohmann::json::parse(rf, nullptr, false);
  if (!refs.is_array()) return "";
  std::string md = "### Stage 2 in the reference views\n\nEach row: training photo | lighting-aware mask (the target's "
                   "reflections, traced) | the target mirrored through the glossy plane on the glossy surface (its "
                   "planar reflection) | the target's shadow (share of the light it took) | inpainting mask | "
                   "inpainted colour\n\n";
  for (const nlohmann::json& r : refs) {
    const std::string name = r.value("view", "");
    const auto v = std::find_if(ds.train.begin(), ds.train.end(), [&](const goris::View& d) { return d.name == name; });
    if (v == ds.train.end()) continue;
    const std::string file = "stage2_" + name + ".png";
    write_png(out / file, tile_row({{v->image, "photo"},
                                    {removed / "lighting_masks" / (name + ".png"), "reflections", true},
                                    {removed / "reflection_masks" / (name + ".png"), "planar refl.", true},
                                    {removed / "shadow" / (name + ".png"), "shadow", true},
                                    {removed / "inpaint_masks" / (name + ".png"), "inpaint mask"},
                                    {removed / "inpainted" / (name + "_rgb.png"), "inpainted"}}));
    md += "![" + name + " stage 2](" + file + ")\n\n";
  }
  return md;
}

// The channels the report shows for an intrinsic run (render/maps/channels.h names), in the paper's order.
constexpr const char* kIntrinsicChannels[] = {"diffuse", "glossy", "f0", "roughness", "normal"};

// The stage-1 mode a run trained in (config.json; --mode auto has written its decision there).
std::string run_mode(const fs::path& run) {
  std::ifstream f(run / "config.json");
  if (!f) throw Error((run / "config.json").string(), "missing: the training step wrote no config");
  return nlohmann::json::parse(f).value("mode", std::string());
}

void write_report(const Options& o, const fs::path& out, const fs::path& run, const fs::path& renders,
                  const StepTimes& times) {
  const goris::Dataset ds = goris::load_dataset(o.data, {});
  std::ifstream mf(run / "metrics.json");
  if (!mf) throw Error((run / "metrics.json").string(), "missing: the evaluation step wrote no metrics");
  const nlohmann::json m = nlohmann::json::parse(mf);
  const std::string mode = run_mode(run);  // what stage 1 trained (--mode auto's decision)

  std::string md = "# GOR-IS Studio demo\n\n";
  md += "Data: `" + o.data + "` (" + ds.format + ", " + std::to_string(ds.train.size()) + " train / " +
        std::to_string(ds.test.size()) + " test views at " + std::to_string(ds.train[0].camera.width) + "x" +
        std::to_string(ds.train[0].camera.height) + ")  \n";
  md += "Training: " + std::to_string(o.iters) + " iterations, " + mode + " mode" +
        (o.mode == "auto" ? std::string(" (chosen by --mode auto)") : std::string()) + ", device `" + m.value("device", "?") +
        "`, " + std::to_string(m.value("gaussians", 0)) + " Gaussians  \n";
  char line[256];
  std::snprintf(line, sizeof line, "Test views against the images with the target (`--gt full`): PSNR %.2f dB, SSIM %.4f  \n",
                m.value("psnr", 0.0), m.value("ssim", 0.0));
  md += line;
  md += "Run folder: `" + run.string() + "` (config, checkpoints, log.csv, point_cloud.ply, metrics.json)\n\n";
  const int n = std::min<int>(o.report_views, int(ds.test.size()));
  const fs::path removed = run / "removal";
  // First what the removal is for: the target and its reflection, before and after.
  if (fs::exists(removed / "metrics.json")) {
    std::ifstream rf(removed / "metrics.json");
    const nlohmann::json r = nlohmann::json::parse(rf);
    const nlohmann::json rm = r.value("removal", nlohmann::json::object());
    if (!rm.empty()) {
      char text[768];
      std::snprintf(text, sizeof text,
                    "## The target and its reflection, before and after\n\nThe changed region (pixels where the views with "
                    "and without the target differ: the target, its reflection and its shadow; %.1f %% of the "
                    "image): PSNR %.2f dB, FLIP %.3f, ghost %.2f (what is left of the target's imprint: 1 = all of "
                    "it, 0 = none).\n\nEach row, cropped to that region: with the target | ground truth without it "
                    "| render after removal\n\n",
                    100.0 * goris::cli::json_number(rm, "region_fraction"), goris::cli::json_number(rm, "region_psnr"),
                    goris::cli::json_number(rm, "region_flip"), goris::cli::json_number(rm, "ghost_ratio"));
      md += text;
      for (int i = 0; i < n; ++i) {
        const auto& v = ds.test[size_t(i) * ds.test.size() / size_t(n)];
        const cv::Mat row = region_crop_row(v, out / "renders_removed" / (v.name + ".png"));
        if (row.empty()) continue;
        const std::string file = "region_" + v.name + ".png";
        write_png(out / file, row);
        md += "![" + v.name + " changed region](" + file + ")\n\n";
      }
    }
  }
  if (fs::is_directory(out / "maps")) {
    md += "## The intrinsic maps\n\nStage 1 splits every view into a diffuse colour D and a glossy reflection G, "
          "traced from the Gaussians' Fresnel F0, roughness and normals (C = D + G, the paper's Eq. 1); removing the target's "
          "Gaussians removes its reflection from G. Each row: photo with the target | D | G | F0 | roughness | "
          "normal\n\n";
    for (int i = 0; i < n; ++i) {
      const auto& v = ds.test[size_t(i) * ds.test.size() / size_t(n)];
      std::vector<Tile> parts = {{v.full_image ? *v.full_image : v.image, "photo"}};
      for (const char* channel : kIntrinsicChannels)
        parts.push_back({out / "maps" / channel / (v.name + ".png"), channel, true});
      const std::string file = "maps_" + v.name + ".png";
      write_png(out / file, tile_row(parts));
      md += "![" + v.name + " intrinsic maps](" + file + ")\n\n";
    }
  }
  md += "## Stage 1\n\nEach row: ground truth | render | depth (TURBO on inverse depth) | normal (n*0.5+0.5)\n\n";
  for (int i = 0; i < n; ++i) {
    const auto& v = ds.test[size_t(i) * ds.test.size() / size_t(n)];
    const fs::path gt = v.full_image ? *v.full_image : v.image;
    const cv::Mat row = comparison_row(gt, renders, v.name);
    const std::string file = "compare_" + v.name + ".png";
    std::vector<unsigned char> png;
    cv::imencode(".png", row, png);
    goris::write_file_bytes(out / file, png.data(), png.size());
    md += "![" + v.name + "](" + file + ")\n\n";
  }
  if (fs::exists(removed / "metrics.json")) {
    std::ifstream rf(removed / "metrics.json");
    const nlohmann::json r = nlohmann::json::parse(rf);
    const nlohmann::json masked = r.value("masked", nlohmann::json::object());
    std::snprintf(line, sizeof line,
                  "\n## After removal\n\nTest views against the scene without the target (`test/r_XXX.png`): PSNR "
                  "%.2f dB, SSIM %.4f, inside the target's region M-PSNR %.2f dB, M-SSIM %.4f  \n",
                  r.value("psnr", 0.0), r.value("ssim", 0.0), masked.value("psnr", 0.0), masked.value("ssim", 0.0));
    md += line;
    md += "Intermediates (masks, reference views, inpainted maps): `" + removed.string() + "`\n\n";
    md += "Each row: ground truth without the target | render after removal | depth | normal\n\n";
    for (int i = 0; i < n; ++i) {
      const auto& v = ds.test[size_t(i) * ds.test.size() / size_t(n)];
      const cv::Mat row = comparison_row(v.image, out / "renders_removed", v.name);
      const std::string file = "removed_" + v.name + ".png";
      std::vector<unsigned char> png;
      cv::imencode(".png", row, png);
      goris::write_file_bytes(out / file, png.data(), png.size());
      md += "![" + v.name + " after removal](" + file + ")\n\n";
    }
    md += stage2_rows(ds, removed, out);
    // Stage 2's own steps, from its report.
    std::ifstream jf(removed / "report.json");
    const nlohmann::json rep = jf ? nlohmann::json::parse(jf, nullptr, false) : nlohmann::json();
    if (rep.is_object() && rep.contains("seconds")) {
      md += "### Time of each stage-2 step\n\n| step | seconds |\n|---|---|\n";
      for (int k = 0; k < goris::kRemovalStepCount; ++k) {  // in the pipeline's order
        const char* step = goris::removal_step_name(goris::RemovalStep(k));
        std::snprintf(line, sizeof line, "| %s | %.1f |\n", step, rep["seconds"].value(step, 0.0));
        md += line;
      }
      md += "\n";
    }
  }
  md += "## Time of each stage\n\n| step | seconds |\n|---|---|\n";
  for (const auto& [title, sec] : times) {
    std::snprintf(line, sizeof line, "| %s | %.1f |\n", title.c_str(), sec);
    md += line;
  }
  md += "\nExported: `cleaned.ply` (the cleaned scene, intrinsic attributes as extra properties) and "
        "`cleaned_baked.ply` (distilled into plain SH: any 3DGS viewer shows it; fidelity against the run in "
        "cleaned_baked.json; a radiance run is plain SH already and is copied), and the baked model as "
        "`cleaned.spz` (Niantic SPZ 3), `cleaned.compressed.ply` (PlayCanvas), `cleaned.splat` (antimatter15) and "
        "`cleaned.glb` (glTF, KHR_gaussian_splatting) "
        "for web viewers and engines; videos: `cleaned_orbit.mp4` (a 10-second orbit of the cleaned scene) and "
        "`before_after.mp4` (the test views with the target | after removal)\n";
  goris::write_file_bytes(out / "report.md", md.data(), md.size());
  double total = 0;
  for (const auto& [title, sec] : times) total += sec;
  std::printf("\n== demo: report %s (%.0f s in all, %s mode)\n", (out / "report.md").string().c_str(), total,
              mode.c_str());
}

void run_demo(const Options& o) {
  const fs::path out = fs::absolute(o.out);
  const fs::path run = out / "run", renders = out / "renders";
  // The demo starts from scratch each time, but only ever clears a folder it made itself.
  if (fs::exists(out) && !fs::is_empty(out)) {
    if (!fs::exists(out / "demo.marker"))
      throw Error(out.string(), "exists and is not a demo folder; choose another --out");
    fs::remove_all(out);
  }
  fs::create_directories(out);
  { std::ofstream(out / "demo.marker") << "written by goris demo\n"; }
  const std::string data = fs::absolute(o.data).string();
  StepTimes times;
  auto step = [&](const std::string& title, std::vector<std::string> args) {
    times.emplace_back(title, run_step(title, std::move(args)));
  };
  step("info", {"info", data});
  step("train", {"train", data, "--out", run.string(), "--mode", o.mode, "--iters", std::to_string(o.iters),
                 "--device", o.device, "--checkpoint-every", "0"});
  step("render test views with all maps",
       {"render", run.string(), "--split", "test", "--out", renders.string(), "--maps", "--device", o.device});
  step("evaluate against the views with the target",
       {"eval", run.string(), "--split", "test", "--gt", "full", "--device", o.device});
  // The intrinsic maps the paper's method reasons with, when stage 1 trained them (--mode auto decides).
  if (run_mode(run) == "intrinsic") {
    fs::create_directories(out / "maps");
    for (const char* channel : kIntrinsicChannels)
      step(std::string("render the test views' ") + channel + " map",
           {"export", run.string(), "--renders", (out / "maps" / channel).string(), "--channel", channel, "--frames",
            std::to_string(o.report_views), "--device", o.device});
  }
  // Stage 2: the target from the data set's object masks, removed with its reflections, evaluated against
  // the after-removal ground truth (test/r_XXX.png).
  const fs::path removed = run / "removal", removed_renders = out / "renders_removed";
  step("select the target from the object masks", {"select", run.string(), "--masks", "--device", o.device});
  step("remove it (stage 2)", {"remove", run.string(), "--device", o.device});
  step("render the cleaned scene", {"render", removed.string(), "--split", "test", "--out",
                                    removed_renders.string(), "--maps", "--device", o.device});
  step("evaluate against the scene without the target",
       {"eval", removed.string(), "--split", "test", "--device", o.device});
  step("export the cleaned scene (intrinsic PLY, a baked PLY any 3DGS viewer shows, and that model as SPZ, "
       "compressed PLY, .splat and GLB)",
       {"export", removed.string(), "--ply", (out / "cleaned.ply").string(), "--baked",
        (out / "cleaned_baked.ply").string(), "--spz", (out / "cleaned.spz").string(), "--compressed-ply",
        (out / "cleaned.compressed.ply").string(), "--splat", (out / "cleaned.splat").string(), "--glb",
        (out / "cleaned.glb").string(), "--iters", std::to_string(std::max(100, o.iters / 4)), "--device",
        o.device});
  step("a 10-second orbit of the cleaned scene",
       {"export", removed.string(), "--video", (out / "cleaned_orbit.mp4").string(), "--seconds", "10", "--device",
        o.device});
  step("the test views before | after removal",
       {"export", removed.string(), "--video", (out / "before_after.mp4").string(), "--before", run.string(),
        "--path", "test", "--fps", "2", "--device", o.device});
  write_report(o, out, run, renders, times);
}

void setup_demo(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand("demo", "Train, remove the target, render and evaluate the embedded default scene; write a report");
  c->add_option("--data", o->data, "Data set (default: the embedded default scene)")->capture_default_str();
  c->add_option("--out", o->out, "Output folder (report.md, images, run/)")->capture_default_str();
  c->add_option("--iters", o->iters, "Training iterations")->capture_default_str()->check(goris::cli::whole(1, goris::cli::kIntMax));
  goris::cli::add_device_option(*c, o->device);
  c->add_option("--mode", o->mode,
                "Stage-1 mode: auto (intrinsic where the data set's glossy masks mark a glossy surface, as on the "
                "embedded scene; else radiance), radiance (fast) or intrinsic")
      ->capture_default_str()
      ->check(CLI::IsMember(goris::cli::enum_name_list<goris::TrainMode>()));
  c->callback([o] { run_demo(*o); });
}

}  // namespace
GORIS_COMMAND(5, setup_demo);
