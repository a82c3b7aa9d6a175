// `goris export RUN [--ply OUT.ply] [--baked OUT.ply] [--spz OUT.spz] [--compressed-ply OUT.compressed.ply]
// [--splat OUT.splat] [--glb OUT.glb] [--renders DIR [--frames N]] [--video OUT.mp4 [--seconds S] [--fps F]
// [--before RUN0]] [--path test|train|orbit] [--channel C] [--iters N] [--device D]`: the
// exports of a run folder (RUN or RUN/removal), see export/run/run_export.h. The standard formats (SPZ,
// compressed PLY, .splat, GLB: core/io/splat_formats.h) hold the plain SH model --baked writes: for an intrinsic
// run the distilled one (one distillation serves --baked and all of them).
// Every output path is checked before any work starts; SIGINT, SIGTERM or SIGHUP during the distillation ends
// it early, the baked model so far is still written (marked "stopped" in its json), the exports after it are
// skipped and the command exits 130, 143 or 129.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_common/command.h"
#include "app/cli_common/number_checks.h"
#include "app/cli_common/stop_signals.h"
#include "core/io/file_bytes.h"
#include "core/io/splat_formats.h"
#include "core/util/error.h"
#include "export/run/run_export.h"
#include "export/run/video.h"
#include "train/run/run_folder.h"
#include "train/run/run_output_guard.h"

namespace {
namespace fs = std::filesystem;
using namespace goris;

struct Options {
  std::string run, ply, baked, spz, compressed_ply, splat, glb, renders, video, before, device = "auto", data;
  std::string path;  // empty: test for --renders, orbit for --video
  std::string channel = "final";
  int frames = 0, iters = 2000, extra_views = -1;
  double seconds = 10.0, fps = 24.0;
  float geometry_lr_scale = 0.0f;
  float sh_lr_scale = 20.0f;  // DistillSettings' default
  std::uint64_t seed = 0;
};

void print_baked(const BakedReport& r) {
  const DistillResult& d = r.distill;
  if (!r.distilled)
    std::printf("baked: radiance run, the model is plain SH already: %s is the --ply export without the extra "
                "properties (baked filter check: %.2f dB against the run's renders)\n",
                r.ply.string().c_str(), d.psnr);
  else
    std::printf("baked: %d iterations%s on %zu target views (%zu interpolated) in %.1f s; fidelity on %zu held-out "
                "(%s) views: PSNR %.2f dB against the run's shaded renders (%.2f dB before distillation)\n",
                d.iterations, d.stopped ? " (stopped)" : "", d.target_views, d.extra_views, d.seconds_total,
                d.holdout_views, r.holdout.c_str(), d.psnr, d.psnr_start);
  if (std::isfinite(r.gt_psnr_run))
    std::printf("against the test images: run %.2f dB, baked %.2f dB\n", r.gt_psnr_run, r.gt_psnr_baked);
  std::printf("wrote %s and %s\n", r.ply.string().c_str(), r.json.string().c_str());
}

// The standard-format outputs asked for: (path, the format the name must have, option).
struct FormatOutput {
  std::string path;
  SplatFormat format;
  const char* option;
};
std::vector<FormatOutput> format_outputs(const Options& o) {
  std::vector<FormatOutput> out;
  if (!o.spz.empty()) out.push_back({o.spz, SplatFormat::Spz, "--spz"});
  if (!o.compressed_ply.empty()) out.push_back({o.compressed_ply, SplatFormat::CompressedPly, "--compressed-ply"});
  if (!o.splat.empty()) out.push_back({o.splat, SplatFormat::Antimatter, "--splat"});
  if (!o.glb.empty()) out.push_back({o.glb, SplatFormat::Glb, "--glb"});
  return out;
}

void run_export(const Options& o) {
  if (!o.path.empty() && o.renders.empty() && o.video.empty())
    throw Error("--path", "--path chooses the cameras of --renders or --video: give one of them");
  if (o.channel != "final" && o.renders.empty() && o.video.empty())
    throw Error("--channel", "--channel chooses what --renders and --video show: give one of them");
  const std::vector<FormatOutput> formats = format_outputs(o);
  if (o.ply.empty() && o.baked.empty() && o.renders.empty() && o.video.empty() && formats.empty())
    throw Error("goris export", "nothing to export: give at least one of --ply OUT.ply (intrinsic PLY), --baked OUT.ply "
                                "(distilled standard 3DGS PLY), --spz OUT.spz, --compressed-ply OUT.compressed.ply, "
                                "--splat OUT.splat, --glb OUT.glb (the baked model in those formats), --renders DIR (PNG frames), "
                                "--video OUT.mp4 (a turntable)");
  std::vector<std::pair<std::string, const char*>> files;
  if (!o.ply.empty()) files.emplace_back(o.ply, "--ply");
  if (!o.baked.empty()) {
    files.emplace_back(o.baked, "--baked");
    files.emplace_back(baked_json_path(o.baked).string(), "--baked's json");
  }
  for (const FormatOutput& f : formats) files.emplace_back(f.path, f.option);
  if (!o.video.empty()) files.emplace_back(o.video, "--video");
  for (size_t i = 0; i < files.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (fs::absolute(files[i].first) == fs::absolute(files[j].first))
        throw Error(files[i].first, std::string(files[j].second) + " and " + files[i].second + " name the same file");
  for (const FormatOutput& f : formats)
    if (splat_format_from_name(f.path) != f.format)
      throw Error(f.path, std::string(f.option) + " needs a file name ending in " +
                              (f.format == SplatFormat::Spz             ? ".spz"
                               : f.format == SplatFormat::CompressedPly ? ".compressed.ply"
                               : f.format == SplatFormat::Glb           ? ".glb"
                                                                        : ".splat"));
  const RenderPath renders_path = parse_render_path(o.path.empty() ? "test" : o.path);
  const RenderPath video_path = parse_render_path(o.path.empty() ? "orbit" : o.path);
  if (!o.video.empty() && fs::path(o.video).extension() != ".mp4")
    throw Error(o.video, "--video writes MPEG-4: the name must end in .mp4");
  // Fail on a bad path now, not after a distillation: never into the data set or over the run's inputs.
  const fs::path run_dir = fs::absolute(o.run);
  OutputGuard guard;
  try {
    guard = run_output_guard(run_dir, read_run_config(run_dir));
  } catch (const Error&) {
  }  // not a run: RunExport below says so, after the paths' own problems
  if (!o.data.empty()) guard.datasets.push_back(fs::absolute(o.data));  // the data set's folder now
  for (const auto& f : files) check_output_file(f.first, guard);
  if (!o.renders.empty()) check_output_dir(o.renders, guard);
  // Temporary files an earlier export left where it was killed mid-write go now.
  for (const auto& f : files) remove_stale_temp_files(fs::absolute(f.first).parent_path());
  if (!o.renders.empty()) remove_stale_temp_files(o.renders);

  const Device device = resolve_device(o.device);
  RunExport ex(o.run, device, o.data);
  const Channel channel = *channel_from_id(o.channel);  // checked by the option
  ex.require_channel(channel);  // before any distillation
  const std::string of_channel = channel == Channel::Final ? "" : " of " + o.channel;
  std::printf("exporting %s (%s run, %zu Gaussians from %s) on %s\n", ex.run_dir().string().c_str(),
              enum_name(ex.config().mode), ex.model().count(), ex.model_source().c_str(), device_name(device));
  std::fflush(stdout);  // before the progress on stderr
  const bool tty = isatty(STDERR_FILENO);

  if (!o.ply.empty()) {
    ex.write_ply(o.ply);
    std::printf("ply: wrote %s (standard 3DGS layout, 3D filter baked in%s)\n", o.ply.c_str(),
                ex.intrinsic() ? ", intrinsic attributes as extra properties" : "");
    std::fflush(stdout);
  }
  // One distillation for --baked and the standard formats of an intrinsic run.
  const bool need_bake = !o.baked.empty() || (!formats.empty() && ex.intrinsic());
  GaussianPly plain;
  if (need_bake) {
    DistillSettings s;
    s.iterations = o.iters;
    s.extra_views = o.extra_views;
    s.geometry_lr_scale = o.geometry_lr_scale;
    s.sh_lr_scale = o.sh_lr_scale;
    s.seed = o.seed;
    s.progress_every = tty ? 10 : 100;
    auto progress = [tty](const DistillProgress& p) {
      const bool train = p.phase == "distilling";
      if (!tty && !train && p.done != p.total) return;
      if (train)
        std::fprintf(stderr, "%sdistilling [%d/%d] loss %.4f  PSNR %5.2f dB  %.1f it/s  ETA %.0f s%s", tty ? "\r" : "",
                     p.done, p.total, p.loss, p.psnr, p.it_per_s, p.eta_s, tty ? "   " : "\n");
      else
        std::fprintf(stderr, "%s%s %d/%d%s", tty ? "\r" : "", p.phase.c_str(), p.done, p.total, tty ? "   " : "\n");
      if (tty && p.done == p.total) std::fprintf(stderr, "\n");
    };
    BakedReport r;
    int stopped_by = 0;
    {
      const cli::StopSignals stop;
      r = ex.bake(s, progress, stop.flag());
      stopped_by = stop.signal();
    }
    if (!o.baked.empty()) {
      ex.write_baked_files(r, o.baked);
      print_baked(r);
    } else {
      std::printf("baked: %d iterations%s, fidelity PSNR %.2f dB against the run's shaded renders on %zu held-out views\n",
                  r.distill.iterations, r.distill.stopped ? " (stopped)" : "", r.distill.psnr, r.distill.holdout_views);
    }
    if (stopped_by) {
      std::printf("interrupted (%s): the distillation stopped early; the exports after --baked are skipped\n",
                  cli::stop_signal_name(stopped_by).c_str());
      cli::set_exit_code(128 + stopped_by);
      return;
    }
    std::fflush(stdout);
    plain = std::move(r.distill.ply);
  } else if (!formats.empty()) {
    plain = ex.radiance_model();
  }
  for (const FormatOutput& f : formats) {
    ex.write_model(f.path, plain);
    const int degree = f.format == SplatFormat::Antimatter ? 0 : plain.sh_degree;  // .splat holds no higher SH
    std::printf("%s: wrote %s (%s, %zu Gaussians, SH degree %d, %ju bytes)\n", f.option + 2, f.path.c_str(),
                splat_format_name(f.format), plain.count, degree, std::uintmax_t(fs::file_size(f.path)));
    std::fflush(stdout);
  }
  if (!o.renders.empty()) {
    const RendersReport r = ex.write_renders(o.renders, renders_path, o.frames, [tty](size_t done, size_t total) {
      if (tty) std::fprintf(stderr, "\rrendering %zu/%zu%s", done, total, done == total ? "\n" : "");
    }, channel);
    std::printf("renders: %zu %s frames%s at %dx%d (%.1f ms each) -> %s, contact sheet %s\n", r.frames.size(),
                render_path_name(renders_path), of_channel.c_str(), r.width, r.height, r.ms_per_frame,
                r.dir.string().c_str(),
                r.contact_sheet.filename().string().c_str());
  }
  if (!o.video.empty()) {
    std::unique_ptr<RunExport> before;
    if (!o.before.empty()) before = std::make_unique<RunExport>(o.before, device);
    VideoSettings vs;
    vs.path = video_path;
    vs.seconds = o.seconds;
    vs.fps = o.fps;
    vs.channel = channel;
    const VideoReport v = write_video(ex, o.video, vs, before.get(), [tty](size_t done, size_t total) {
      if (tty) std::fprintf(stderr, "\rvideo frame %zu/%zu%s", done, total, done == total ? "\n" : "");
    });
    std::printf("video: %d %s frames%s at %dx%d, %.3g fps (%.1f s)%s -> %s\n", v.frames,
                render_path_name(video_path), of_channel.c_str(), v.width, v.height, v.fps,
                double(v.frames) / v.fps, v.side_by_side ? ", before | after" : "", v.file.string().c_str());
  }
}

void setup_export(CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* c = root.add_subcommand(
      "export", "Export a run (RUN or RUN/removal): intrinsic PLY, distilled standard 3DGS PLY, rendered frames");
  c->add_option("run", o->run, "Run folder (goris train) or stage-2 result (RUN/removal)")->required();
  c->add_option("--ply", o->ply,
                "Write the model in the standard 3DGS layout, intrinsic attributes as extra properties, 3D filter "
                "baked into scales and opacities");
  c->add_option("--baked", o->baked,
                "Write a standard SH-only 3DGS model distilled from the run's shaded renders (any viewer shows it), "
                "and OUT.json beside it with the fidelity PSNR on held-out views");
  c->add_option("--spz", o->spz,
                "Write the baked model (as --baked) as Niantic SPZ version 3: gzip, quantized, about a tenth of the PLY");
  c->add_option("--compressed-ply", o->compressed_ply,
                "Write the baked model (as --baked) as a PlayCanvas compressed PLY (OUT.compressed.ply: chunks of 256, "
                "32 bits per attribute)");
  c->add_option("--splat", o->splat,
                "Write the baked model (as --baked) in the antimatter15 .splat layout of web viewers (32 bytes per "
                "Gaussian, no higher SH)");
  c->add_option("--glb", o->glb,
                "Write the baked model (as --baked) as glTF binary with KHR_gaussian_splatting (float32, lossless)");
  auto* renders = c->add_option("--renders", o->renders,
                                "Write one PNG per frame from the run's renderer, contact_sheet.png and cameras.json");
  auto* video = c->add_option("--video", o->video,
                              "Write an MPEG-4 video (OUT.mp4) from the run's renderer along --path (default orbit: "
                              "one turn in --seconds)");
  c->add_option("--seconds", o->seconds, "--video on the orbit: the length of the turn (default 10)")
      ->check(cli::real(0.01, 600.0))
      ->needs(video);
  c->add_option("--fps", o->fps, "--video: frames per second (default 24)")->check(cli::real(1.0, 240.0))->needs(video);
  c->add_option("--before", o->before,
                "--video: a run with the target (the stage-1 RUN of a RUN/removal) rendered beside it, before | after")
      ->needs(video);
  c->add_option("--path", o->path,
                "Cameras for --renders (default test) and --video (default orbit): test (the data set's test views), "
                "train, or orbit (a circle around the scene at the cameras' mean height and distance, looking at "
                "where they look)")
      ->check(CLI::IsMember({"test", "train", "orbit"}));
  c->add_option("--channel", o->channel,
                "What --renders and --video show: final (default), or a channel of the render as the editor's "
                "viewports show it: " + channel_id_list() + " (intrinsic channels need an intrinsic run; the two "
                "masks are files of the training views, not renders)")
      ->check([](const std::string& s) {
        return channel_from_id(s) ? std::string() : "unknown channel '" + s + "' (known: " + channel_id_list() + ")";
      });
  c->add_option("--frames", o->frames, "Orbit: number of frames (default 36); test/train: that many evenly spaced views")
      ->check(cli::whole(0, 100000))
      ->needs(renders);
  c->add_option("--iters", o->iters, "Distillation iterations for --baked, and for the standard formats of an intrinsic run (default 2000)")
      ->check(cli::whole(1, cli::kIntMax));
  c->add_option("--extra-views", o->extra_views,
                "Cameras interpolated between training cameras as extra distillation targets (default: as many as "
                "the training cameras)")
      ->check(cli::whole(0, 100000));
  c->add_option("--geometry-lr", o->geometry_lr_scale,
                "Position/scale/rotation/opacity learning rates during distillation, as a factor of the run's "
                "(default 0: geometry frozen)")
      ->check(cli::real(0, cli::kRealMax));
  c->add_option("--sh-lr", o->sh_lr_scale, "SH learning rates during distillation, as a factor of the run's (default 20)")
      ->check(cli::real(1e-30, cli::kRealMax));
  c->add_option("--seed", o->seed, "Seed of the distillation's view order and interpolated cameras")
      ->check(cli::whole(0, cli::kSeedMax));
  cli::add_device_option(*c, o->device);
  cli::add_data_option(*c, o->data);
  c->callback([o] { run_export(*o); });
}

}  // namespace
GORIS_COMMAND(60, setup_export);
