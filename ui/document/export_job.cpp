#include "ui/document/export_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/compute/device.h"
#include "core/util/duration_text.h"
#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

// Thrown from the library's progress callbacks to end an export at the user's request.
struct ExportCancelled {};

std::string fixed(double v, int digits) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

}  // namespace

fs::path baked_format_path(const fs::path& baked, SplatFormat format) {
  const char* ext = format == SplatFormat::Spz             ? ".spz"
                    : format == SplatFormat::CompressedPly ? ".compressed.ply"
                    : format == SplatFormat::Antimatter    ? ".splat"
                    : format == SplatFormat::Glb           ? ".glb"
                                                           : ".ply";
  return baked.parent_path() / (baked.stem().string() + ext);
}

void check_export_request(const ExportRequest& r) {
  if (r.run_dir.empty()) throw Error("export", "no run folder to export (train a model or open a run first)");
  if (r.ply.empty() && r.baked.empty() && r.renders.empty())
    throw Error("export", "nothing to export: choose the intrinsic PLY, the baked PLY or renders");
  if (!r.ply.empty() && !r.baked.empty() &&
      fs::absolute(r.ply).lexically_normal() == fs::absolute(r.baked).lexically_normal())
    throw Error(r.ply.string(), "the intrinsic PLY and the baked PLY are the same file");
  if (!r.baked.empty() && r.baked_iterations <= 0)
    throw Error(r.baked.string(),
                "the distillation needs at least 1 iteration (" + std::to_string(r.baked_iterations) + " given)");
  if (!r.baked_formats.empty() && r.baked.empty())
    throw Error("export", "SPZ, compressed PLY and .splat hold the baked model: choose the baked PLY too");
  for (SplatFormat f : r.baked_formats)
    if (fs::absolute(baked_format_path(r.baked, f)).lexically_normal() == fs::absolute(r.baked).lexically_normal() ||
        (!r.ply.empty() && fs::absolute(baked_format_path(r.baked, f)).lexically_normal() == fs::absolute(r.ply).lexically_normal()))
      throw Error(baked_format_path(r.baked, f).string(), std::string("the ") + splat_format_name(f) +
                                                              " file would replace another export: rename the baked PLY");
  if (!r.renders.empty() && r.frames < 0)
    throw Error(r.renders.string(), "the frame count must be >= 0 (" + std::to_string(r.frames) + " given)");
}

const char* export_part_name(ExportPart p) {
  switch (p) {
    case ExportPart::Load:
      return "load the run";
    case ExportPart::Ply:
      return "intrinsic PLY";
    case ExportPart::Baked:
      return "baked PLY";
    case ExportPart::Renders:
      return "renders";
  }
  return "?";
}

// A distillation iteration (rasterizer forward + backward) measured at about 0.8 renders of an intrinsic
// run; loading and the PLY are a few renders' worth.
constexpr double kIterationCost = 0.8;

double ExportProgress::weight(ExportPart p) const {
  const ExportPartStatus& s = parts[size_t(p)];
  if (!s.wanted) return 0.0;
  switch (p) {
    case ExportPart::Load:
      return 2.0;
    case ExportPart::Ply:
      return 0.5;
    case ExportPart::Baked:
      return double(std::max(teacher_views, 1)) + kIterationCost * double(baked_iterations);
    case ExportPart::Renders:
      return double(std::max(frames, 1));
  }
  return 0.0;
}

double ExportProgress::baked_render_share() const {
  const double renders = double(std::max(teacher_views, 1));
  return renders / (renders + kIterationCost * double(baked_iterations));
}

double ExportProgress::fraction() const {
  double total = 0, done = 0;
  for (int k = 0; k < kExportPartCount; ++k) {
    const double w = weight(ExportPart(k));
    total += w;
    done += w * (parts[size_t(k)].complete ? 1.0 : std::clamp(parts[size_t(k)].fraction, 0.0, 1.0));
  }
  return total > 0 ? done / total : 0.0;
}

void ExportJob::start(const ExportRequest& request) {
  if (const JobState s = job_.state(); job_active(s))
    throw Error(std::string("export: an export is ") + job_state_name(s) + ": wait for it or cancel it first");
  check_export_request(request);
  ExportRequest rq = request;
  rq.run_dir = fs::absolute(request.run_dir);
  for (fs::path* p : {&rq.ply, &rq.baked, &rq.renders})
    if (!p->empty()) *p = fs::absolute(*p).lexically_normal();
  ExportProgress progress;
  // Rough counts until the run is loaded (then the real ones).
  progress.baked_iterations = rq.baked_iterations;
  progress.teacher_views = 100;
  progress.frames = rq.frames > 0                         ? rq.frames
                    : rq.render_path == RenderPath::Orbit ? kDefaultOrbitFrames
                                                          : 20;
  const fs::path* paths[] = {&rq.run_dir, &rq.ply, &rq.baked, &rq.renders};
  for (int k = 0; k < kExportPartCount; ++k) {
    progress.parts[size_t(k)].wanted = !paths[k]->empty();
    progress.parts[size_t(k)].path = *paths[k];
  }
  request_.set(rq);
  progress_.set(std::move(progress));
  result_.set(ExportResult());
  distilling_ = false;
  stop_distill_ = false;
  job_.start([this, rq](const std::atomic<bool>&) { return work(rq); });
}

void ExportJob::cancel() {
  if (job_.state() != JobState::Running) return;
  job_.cancel("cancelling: stops at the next progress check");
  stop_distill_ = true;  // the distillation's loop returns at once, and its next report ends the export
}

void ExportJob::finish_early() {
  if (job_.state() == JobState::Running && distilling_) stop_distill_ = true;
}

bool ExportJob::distilling() const { return job_.state() == JobState::Running && distilling_ && !stop_distill_; }

void ExportJob::check_cancel() const {
  if (job_.state() == JobState::Cancelling) throw ExportCancelled{};
}

void ExportJob::begin_part(ExportPart p) {
  check_cancel();
  part_started_ = std::chrono::steady_clock::now();
  const fs::path path = progress_.with([&](ExportProgress& progress) {
    ExportPartStatus& s = progress.parts[size_t(p)];
    s.started = true;
    progress.current = int(p);
    return s.path;
  });
  job_.set_status(std::string(export_part_name(p)) + ": " + path.string());
}

void ExportJob::update_part(ExportPart p, double fraction, const std::string& detail) {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - part_started_).count();
  progress_.with([&](ExportProgress& progress) {
    ExportPartStatus& s = progress.parts[size_t(p)];
    s.fraction = std::clamp(fraction, 0.0, 1.0);
    s.detail = detail;
    s.seconds = seconds;
  });
  job_.set_status(std::string(export_part_name(p)) + ": " + detail);
  check_cancel();
}

void ExportJob::end_part(ExportPart p, const std::string& detail) {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - part_started_).count();
  progress_.with([&](ExportProgress& progress) {
    ExportPartStatus& s = progress.parts[size_t(p)];
    s.fraction = 1.0;
    s.complete = true;
    s.detail = detail;
    s.seconds = seconds;
  });
}

std::string ExportJob::work(const ExportRequest& rq) {
  ExportPart part = ExportPart::Load;
  auto add_written = [this](const fs::path& p, const std::string& line) {
    result_.with([&](ExportResult& r) {
      r.written.push_back(p);
      r.summary += (r.summary.empty() ? "" : "\n") + line;
    });
  };
  try {
    // Every output path first, so that a typo fails now and not after a distillation. The dialog proposes
    // files in a folder of their own (RUN/export): that one folder is made when its parent exists, as the
    // CLI makes an output folder; deeper missing paths are refused.
    auto check_file = [](const fs::path& f) {
      const fs::path dir = fs::absolute(f).parent_path();
      std::error_code ec;
      if (!fs::exists(dir, ec) && fs::is_directory(dir.parent_path(), ec)) check_output_dir(dir);
      check_output_file(f);
    };
    part = ExportPart::Ply;
    if (!rq.ply.empty()) check_file(rq.ply);
    part = ExportPart::Baked;
    if (!rq.baked.empty()) check_file(rq.baked);
    for (SplatFormat f : rq.baked_formats) check_file(baked_format_path(rq.baked, f));
    part = ExportPart::Renders;
    if (!rq.renders.empty()) check_output_dir(rq.renders);

    part = ExportPart::Load;
    begin_part(part);
    update_part(part, 0.0, "reading " + rq.run_dir.string());
    const Device device = resolve_device(rq.device);
    RunExport ex(rq.run_dir, device);
    end_part(part, std::string(ex.intrinsic() ? "intrinsic" : "radiance") + " run, " +
                       std::to_string(ex.model().count()) + " Gaussians from " +
                       fs::path(ex.model_source()).filename().string() + " on " + device_name(device));
    {
      // The real counts, for the overall progress. The distillation renders the training views, as many
      // interpolated ones and the held-out views (test, or 16 orbit cameras); a radiance run is baked as it
      // is (no training, only the held-out views).
      const size_t n = rq.renders.empty() ? 0 : ex.path_cameras(rq.render_path, rq.frames).size();
      const size_t holdout = ex.dataset().test.empty() ? 16 : ex.dataset().test.size();
      progress_.with([&](ExportProgress& progress) {
        progress.frames = int(n);
        if (!ex.intrinsic()) progress.baked_iterations = 0;
        progress.teacher_views = int(holdout + (ex.intrinsic() ? 2 * ex.dataset().train.size() : 0));
      });
    }

    if (!rq.ply.empty()) {
      part = ExportPart::Ply;
      begin_part(part);
      ex.write_ply(rq.ply);
      const std::string line = std::string("intrinsic PLY: ") + rq.ply.string() +
                               (ex.intrinsic() ? " (3DGS layout, intrinsic attributes as extra properties)"
                                               : " (3DGS layout; a radiance run has no intrinsic attributes)");
      end_part(part, "wrote " + rq.ply.filename().string());
      add_written(rq.ply, line);
    }

    if (!rq.baked.empty()) {
      part = ExportPart::Baked;
      begin_part(part);
      DistillSettings s;
      s.iterations = rq.baked_iterations;
      s.progress_every = 1;  // every iteration: a cancel is seen at once
      const BakedReport r = ex.write_baked(
          rq.baked, s,
          [&](const DistillProgress& p) {
            const double f = p.total > 0 ? double(p.done) / double(p.total) : 1.0;
            const double share = progress_.with([&](ExportProgress& progress) {
              if (p.phase == "targets") progress.teacher_views = p.total;
              return progress.baked_render_share();
            });
            if (p.phase == "targets") {
              update_part(part, share * f,
                          "rendering the run's views " + std::to_string(p.done) + "/" + std::to_string(p.total));
            } else if (p.phase == "distilling") {
              distilling_ = p.done < p.total;
              update_part(part, share + (1 - share) * 0.98 * f,
                          "distilling " + std::to_string(p.done) + "/" + std::to_string(p.total) + ": PSNR " +
                              fixed(p.psnr, 2) + " dB, " + fixed(p.it_per_s, 1) + " it/s, ETA " +
                              duration_text(p.eta_s));
            } else {
              distilling_ = false;
              update_part(part, 0.99, "fidelity measured on the held-out views; writing");
            }
          },
          &stop_distill_);
      check_cancel();  // a cancel during the last steps: the file is complete, but report what was asked
      std::vector<std::pair<fs::path, SplatFormat>> others;
      for (SplatFormat f : rq.baked_formats) {
        others.emplace_back(baked_format_path(rq.baked, f), f);
        ex.write_model(others.back().first, r.distill.ply);
      }
      const DistillResult& d = r.distill;
      std::string detail;
      if (r.distilled)
        detail = std::to_string(d.iterations) + " iterations" + (d.stopped ? " (stopped early)" : "") + ", PSNR " +
                 fixed(d.psnr, 2) + " dB against the run's renders (" + fixed(d.psnr_start, 2) + " dB before)";
      else
        detail = "radiance run: the model is plain SH already (PSNR " + fixed(d.psnr, 2) + " dB against its renders)";
      end_part(part, detail);
      {
        // The report without the model and the held-out images (the GUI copies results every frame).
        BakedReport light = r;
        light.distill.ply = GaussianPly();
        light.distill.holdout_images.clear();
        result_.with([&](ExportResult& res) { res.baked = std::move(light); });
      }
      add_written(r.ply, "baked PLY: " + r.ply.string() + " (" + detail + ")");
      add_written(r.json, "baked PLY report: " + r.json.string());
      for (const auto& [path, f] : others)
        add_written(path, std::string("baked model as ") + splat_format_name(f) + ": " + path.string() + " (" +
                              std::to_string(fs::file_size(path)) + " bytes)");
    }

    if (!rq.renders.empty()) {
      part = ExportPart::Renders;
      begin_part(part);
      const RendersReport r = ex.write_renders(rq.renders, rq.render_path, rq.frames, [&](size_t done, size_t total) {
        update_part(part, double(done) / double(std::max<size_t>(total, 1)),
                    "frame " + std::to_string(done) + "/" + std::to_string(total));
      });
      const std::string detail = std::to_string(r.frames.size()) + " " + render_path_name(rq.render_path) +
                                 " frames at " + std::to_string(r.width) + "x" + std::to_string(r.height) + ", " +
                                 fixed(r.ms_per_frame, 0) + " ms each";
      end_part(part, detail);
      result_.with([&](ExportResult& res) { res.renders = r; });
      add_written(r.dir, "renders: " + r.dir.string() + " (" + detail + ", contact_sheet.png, cameras.json)");
    }

    std::string paths;
    for (const fs::path& p : result().written)
      if (p.extension() != ".json") paths += (paths.empty() ? "" : ", ") + p.string();
    return "exported " + paths;
  } catch (const ExportCancelled&) {
    std::string kept;
    for (const fs::path& p : result().written) kept += (kept.empty() ? "" : ", ") + p.filename().string();
    std::string line = "cancelled during " + std::string(export_part_name(part));
    if (part == ExportPart::Renders)
      line += " (the frames written so far are complete files; no contact sheet or cameras.json)";
    line += kept.empty() ? "; nothing was written" : "; kept " + kept;
    throw JobCancelled(line);
  } catch (const std::exception& e) {
    throw Error(std::string(export_part_name(part)) + ": " + e.what());
  }
}

}  // namespace goris::ui
