#include "ui/script/script_runner.h"

#include <algorithm>
#include <cstdio>

#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;
using Kind = ScriptAction::Kind;

ScriptRunner::ScriptRunner(std::vector<ScriptAction> actions, std::string source)
    : actions_(std::move(actions)), source_(std::move(source)) {
  if (actions_.empty()) status_ = Status::Finished;
}

int ScriptRunner::current_line() const { return next_ < actions_.size() ? actions_[next_].line : 0; }

void ScriptRunner::fail(const ScriptAction& a, const std::string& problem) {
  status_ = Status::Failed;
  error_ = source_ + ":" + std::to_string(a.line) + ": " + action_name(a.kind) + ": " + problem;
}

ScriptRunner::Status ScriptRunner::step(ScriptHost& host) {
  if (status_ != Status::Running) return status_;
  const ScriptAction& a = actions_[next_];
  bool done = false;
  try {
    done = run_action(host, a);
  } catch (const std::exception& e) {
    fail(a, e.what());
    return status_;
  }
  if (status_ != Status::Running) return status_;
  if (done) {
    phase_ = 0;
    if (a.kind == Kind::Quit || ++next_ == actions_.size()) status_ = Status::Finished;
  }
  return status_;
}

bool ScriptRunner::run_action(ScriptHost& host, const ScriptAction& a) {
  AppState& st = host.state();
  switch (a.kind) {
    case Kind::Open:
      if (phase_ == 0) {
        st.open(a.path);
        phase_ = 1;
        return false;
      }
      if (st.opening()) return false;
      if (!st.open_error().empty()) {
        fail(a, st.open_error());
        return false;
      }
      return host.settled();
    case Kind::Out:
      st.run_folder = fs::absolute(a.path);
      return true;
    case Kind::Set:
      st.add_override(a.key, a.value);
      return true;
    case Kind::Train: {
      if (phase_ == 0) {
        st.start_training(a.count, /*more=*/true);
        phase_ = 1;
        return false;
      }
      const JobState s = st.session().state();
      if (s == JobState::Error) {
        fail(a, st.session().status());
        return false;
      }
      if (s != JobState::Done) return false;
      if (phase_ == 1) {
        const TrainProgress p = st.session().progress();
        std::printf("trained to iteration %d: loss %.4f, PSNR %.2f dB, %zu Gaussians (%s)\n", p.iteration, p.loss,
                    p.psnr, p.gaussians, st.session().status().c_str());
        const FrameStats f = host.training_frame_stats();
        if (f.frames > 0)
          std::printf("GUI while training: %ld frames, %.1f ms mean, %.1f ms max\n", f.frames, f.mean_ms, f.max_ms);
        std::fflush(stdout);
        phase_ = 2;
      }
      return host.settled();
    }
    case Kind::Grid:
      if (phase_ == 0) {
        st.set_grid_count(a.count);
        st.settings().show_grid = a.count > 0;
        phase_ = 1;
      }
      return host.settled();
    case Kind::Panels:
      if (phase_ == 0) {
        host.show_panels(a.names);
        phase_ = 1;
      }
      return host.settled();
    case Kind::Channel:
      if (phase_ == 0) {
        st.set_channel(a.viewport, a.channel);
        phase_ = 1;
      }
      return host.settled();
    case Kind::Snap:
      if (phase_ == 0) {
        st.snap(size_t(a.camera), a.test_split);
        phase_ = 1;
      }
      return host.settled();
    case Kind::Compare:
      if (phase_ == 0) {
        st.set_compare(*compare_mode_from_id(a.mode), a.split);
        phase_ = 1;
      }
      return host.settled();
    case Kind::CompareWith:
      if (phase_ == 0) {
        if (a.what == "before" && !st.has_before())
          throw Error("compare_with before: the shown scene is not a cleaned scene whose run is there");
        st.compare_with_before = a.what == "before";
        phase_ = 1;
      }
      return host.settled();
    case Kind::BeforeAfter:
      if (phase_ == 0) {
        if (!host.settled()) return false;
        st.show_before(a.what == "before");
        phase_ = 1;
      }
      return host.settled();
    case Kind::Click:
    case Kind::SelectClick: {
      const bool strict = a.kind == Kind::SelectClick;
      return run_selection_edit(host, a, strict, [&]() -> std::uint64_t {
        const glm::vec2 size = host.main_image_size();
        const float x = a.x_fraction ? std::min(a.x * size.x, size.x - 0.5f) : a.x;
        const float y = a.y_fraction ? std::min(a.y * size.y, size.y - 0.5f) : a.y;
        const SelectMode mode = *select_mode_from_id(a.select_mode);
        return strict ? st.select_click(x, y, size.x, size.y, mode) : st.mouse_click(x, y, size.x, size.y, mode);
      });
    }
    case Kind::SelectGrow:
      return run_selection_edit(host, a, true, [&] { return st.select_grow(a.grow); });
    case Kind::SelectLabels:
      return run_selection_edit(host, a, true, [&] { return st.select_labels(); });
    case Kind::SelectMasks:
      return run_selection_edit(host, a, true, [&] { return st.select_masks(); });
    case Kind::SelectRect:
    case Kind::SelectPolygon:
    case Kind::SelectBrush:
      return run_selection_edit(host, a, true, [&]() -> std::uint64_t {
        const glm::vec2 size = host.main_image_size();
        std::vector<glm::vec2> pts;
        for (size_t k = 0; k + 1 < a.coords.size(); k += 2)
          pts.push_back({a.coords[k].fraction ? a.coords[k].value * size.x : a.coords[k].value,
                         a.coords[k + 1].fraction ? a.coords[k + 1].value * size.y : a.coords[k + 1].value});
        const SelectMode mode = *select_mode_from_id(a.select_mode);
        if (a.kind == Kind::SelectRect) return st.select_rect(pts[0], pts[1], size, mode);
        if (a.kind == Kind::SelectPolygon) return st.select_polygon(pts, size, mode);
        const float radius = a.radius.fraction ? a.radius.value * size.x : a.radius.value;
        return st.select_brush(pts, radius, size, mode);
      });
    case Kind::SelectThrough:
      st.tools.through_all = a.what == "all";
      return true;
    case Kind::SelectTool:
      if (phase_ == 0) {
        st.tools.tool = *select_tool_from_id(a.what);
        if (st.tools.volume_tool()) {
          st.place_volumes_if_needed();
          std::printf("the %s\n", describe(st.tools.volume()).c_str());
          std::fflush(stdout);
        }
        phase_ = 1;
      }
      return host.settled();
    case Kind::SelectSphere:
    case Kind::SelectBox:
      return run_selection_edit(host, a, true, [&] {
        VolumeRegion v;
        v.kind = a.kind == Kind::SelectBox ? VolumeRegion::Kind::Box : VolumeRegion::Kind::Sphere;
        v.centre = {a.values[0], a.values[1], a.values[2]};
        if (v.kind == VolumeRegion::Kind::Sphere) {
          v.radius = a.values[3];
          st.tools.sphere = v;
        } else {
          v.half_extent = {a.values[3], a.values[4], a.values[5]};
          if (a.values.size() == 9) v.rotation_degrees = {a.values[6], a.values[7], a.values[8]};
          st.tools.box = v;
        }
        st.tools.volumes_placed = true;  // the panel and the gizmo show the volume the script used
        return st.select_volume(v, *select_mode_from_id(a.select_mode));
      });
    case Kind::SelectColour:
      return run_selection_edit(host, a, true, [&] {
        st.tools.colour = {a.values[0], a.values[1], a.values[2]};
        st.tools.colour_distance = a.values[3];
        return st.select_colour(st.tools.colour, a.values[3], *select_mode_from_id(a.select_mode));
      });
    case Kind::Invert:
      return run_selection_edit(host, a, true, [&] { return st.select_invert(); });
    case Kind::GrowStep:
    case Kind::ShrinkStep:
      return run_selection_edit(host, a, true,
                                [&] { return st.select_step(a.kind == Kind::GrowStep ? a.count : -a.count); });
    case Kind::Hide:
      return run_selection_edit(host, a, true, [&] { return st.hide_selected(); });
    case Kind::Lock:
      return run_selection_edit(host, a, true, [&] { return st.lock_selected(); });
    case Kind::Unhide:
      return run_selection_edit(host, a, true, [&] { return st.unhide_all(); });
    case Kind::Unlock:
      return run_selection_edit(host, a, true, [&] { return st.unlock_all(); });
    case Kind::UseAsTargetMasks:
      return run_selection_edit(host, a, true, [&] { return st.use_as_target_masks(a.path); });
    case Kind::Drag:
      return run_drag(host, a);
    case Kind::Press:
      return run_press(host, a);
    case Kind::DragHandle:
      return run_drag_handle(host, a);
    case Kind::TwoClick:
      return run_two_click(host, a);
    case Kind::ExpectSelected: {
      if (!host.settled()) return false;
      const SelectionView v = st.selection().view();
      if (v.selected < size_t(a.count) || v.selected > size_t(a.count_max)) {
        fail(a, std::to_string(v.selected) + " Gaussians are selected, expected " + std::to_string(a.count) +
                    (a.count_max != a.count ? ".." + std::to_string(a.count_max) : ""));
        return false;
      }
      std::printf("%zu of %zu Gaussians selected (%zu hidden, %zu locked)\n", v.selected, v.total, v.hidden_count,
                  v.locked_count);
      std::fflush(stdout);
      return true;
    }
    case Kind::Undo:
      return run_selection_edit(host, a, true, [&] { return st.undo_selection(); });
    case Kind::Redo:
      return run_selection_edit(host, a, true, [&] { return st.redo_selection(); });
    case Kind::SaveSelection: {
      if (!host.settled()) return false;
      const fs::path json = st.save_selection();
      std::printf("saved the selection to %s\n", json.string().c_str());
      std::fflush(stdout);
      return true;
    }
    case Kind::Remove:
    case Kind::RemoveWait:
      return run_remove(host, a, a.kind == Kind::Remove);
    case Kind::RemoveStart:
      if (!host.settled()) return false;
      st.start_removal(a.count);
      return true;
    case Kind::RemoveCancel: {
      if (phase_ == 0) {
        if (!st.removal().active()) throw Error("no removal is running");
        st.removal().cancel();
        phase_ = 1;
      }
      if (st.removal().active()) return false;
      if (st.removal().state() != JobState::Cancelled)
        fail(a, std::string("the removal ended ") + job_state_name(st.removal().state()) + " before it stopped: " +
                    st.removal().status());
      return true;
    }
    case Kind::ExpectStepComplete: {
      const RemovalProgressTracker p = st.removal().progress();
      std::string missing;
      for (int k = 0; k < kRemovalStepCount; ++k) {
        const RemovalStepStatus& s = p.steps()[size_t(k)];
        if (s.complete) continue;
        char b[96];
        std::snprintf(b, sizeof b, "%s%s at %.0f %%", missing.empty() ? "" : ", ", removal_step_name(RemovalStep(k)),
                      100.0 * double(s.fraction()));
        missing += b;
      }
      if (!missing.empty()) {
        fail(a, "not every stage-2 step reached 100 %: " + missing);
        return false;
      }
      std::printf("every stage-2 step reached 100 %%\n");
      std::fflush(stdout);
      return true;
    }
    case Kind::ExportDialog:
      if (phase_ == 0) {
        st.show_export_dialog = a.what == "open";
        phase_ = 1;
      }
      return host.settled();
    case Kind::ExportFrom:
      if (a.what == "removal" && st.removal_result().empty())
        throw Error("the current run has no cleaned scene (RUN/removal with a model): remove first");
      st.export_from_removal = a.what == "removal";
      return true;
    case Kind::Export:
      return run_job_line(host, a, JobLine::Run, export_lines(st, a));
    case Kind::ExportStart:
      return run_job_line(host, a, JobLine::Start, export_lines(st, a));
    case Kind::ExportWait:
      return run_job_line(host, a, JobLine::Wait, export_lines(st, a));
    case Kind::ExportCancel:
      return run_job_line(host, a, JobLine::Cancel, export_lines(st, a));
    case Kind::ExpectExportError:
      return run_job_line(host, a, JobLine::ExpectError, export_lines(st, a));
    case Kind::ImportCapture:
      return run_job_line(host, a, JobLine::Run, import_lines(st, a)) && imported_data_open(host, a);
    case Kind::ImportCaptureStart:
      return run_job_line(host, a, JobLine::Start, import_lines(st, a));
    case Kind::ImportWait:
      return run_job_line(host, a, JobLine::Wait, import_lines(st, a)) && imported_data_open(host, a);
    case Kind::ImportCancel:
      return run_job_line(host, a, JobLine::Cancel, import_lines(st, a));
    case Kind::ExpectImportError:
      return run_job_line(host, a, JobLine::ExpectError, import_lines(st, a));
    case Kind::Screenshot:
    case Kind::ScreenshotNow:
      if (phase_ == 0) {
        if (a.kind == Kind::Screenshot && !host.settled()) return false;
        host.request_screenshot(fs::absolute(a.path));
        phase_ = 1;
        return false;
      }
      if (host.screenshot_pending()) return false;
      if (const auto err = host.screenshot_error()) {
        fail(a, *err);
        return false;
      }
      std::printf("screenshot %s\n", fs::absolute(a.path).string().c_str());
      std::fflush(stdout);
      return true;
    case Kind::WaitFrames:
      if (phase_ == 0) {
        frames_left_ = a.count;
        phase_ = 1;
      }
      return frames_left_-- <= 0;
    case Kind::Quit:
      host.quit();
      return true;
  }
  return true;
}

bool ScriptRunner::run_selection_edit(ScriptHost& host, const ScriptAction& a, bool strict,
                                      const std::function<std::uint64_t()>& start) {
  AppState& st = host.state();
  if (phase_ == 0) {
    if (!host.settled()) return false;
    job_ = start();
    phase_ = 1;
    return false;
  }
  if (phase_ == 1) {
    if (job_ != 0 && !st.selection().finished(job_)) return false;
    if (const auto err = job_ != 0 ? st.selection().job_error(job_) : std::nullopt; err && strict) {
      fail(a, *err);
      return false;
    }
    phase_ = 2;
  }
  return host.settled();
}

bool ScriptRunner::run_drag(ScriptHost& host, const ScriptAction& a) {
  if (phase_ == 0) {
    if (!host.settled()) return false;
    const glm::vec2 size = host.main_image_size(), origin = host.main_image_origin();
    if (!(size.x > 0 && size.y > 0)) throw Error("the main viewport shows no image");
    std::vector<glm::vec2> pts;
    for (size_t k = 0; k + 1 < a.coords.size(); k += 2)
      pts.push_back(origin + glm::vec2(a.coords[k].fraction ? a.coords[k].value * size.x : a.coords[k].value,
                                       a.coords[k + 1].fraction ? a.coords[k + 1].value * size.y : a.coords[k + 1].value));
    ScriptedMouse m;
    m.shift = a.modifier == "shift";
    m.ctrl = a.modifier == "ctrl";
    m.alt = a.modifier == "alt";
    // Hover, press, move in small steps through every point, release, then the real pointer again.
    drag_.clear();
    m.pos = pts[0];
    drag_.push_back(m);
    m.left_down = true;
    drag_.push_back(m);
    constexpr int kSteps = 4;
    for (size_t k = 1; k < pts.size(); ++k)
      for (int i = 1; i <= kSteps; ++i) {
        m.pos = pts[k - 1] + (pts[k] - pts[k - 1]) * (float(i) / float(kSteps));
        drag_.push_back(m);
      }
    m.left_down = false;
    drag_.push_back(m);
    drag_.push_back(m);
    phase_ = 1;
  }
  if (phase_ == 1) {
    if (!drag_.empty()) {
      host.set_scripted_mouse(drag_.front());
      drag_.erase(drag_.begin());
      return false;
    }
    host.set_scripted_mouse(std::nullopt);
    frames_left_ = 2;  // the release's edit is queued while that frame draws
    phase_ = 2;
  }
  if (frames_left_-- > 0) return false;
  if (!host.settled()) return false;
  AppState& st = host.state();
  if (st.tools.volume_tool() && a.kind != Kind::Press) {  // where the handles left the volume
    std::printf("the %s\n", describe(st.tools.volume()).c_str());
    std::fflush(stdout);
  }
  return true;
}

bool ScriptRunner::run_remove(ScriptHost& host, const ScriptAction& a, bool start) {
  AppState& st = host.state();
  if (phase_ == 0) {
    if (start) {
      if (!host.settled()) return false;
      st.start_removal(a.count);
    } else if (!st.removal().active() && st.removal().state() == JobState::Idle) {
      throw Error("no removal was started");
    }
    phase_ = 1;
    return false;
  }
  if (phase_ == 1) {
    const JobState s = st.removal().state();
    if (s == JobState::Running || s == JobState::Cancelling) return false;
    if (s != JobState::Done) {
      fail(a, std::string(job_state_name(s)) + ": " + st.removal().status());
      return false;
    }
    std::printf("removal %s (%.1f s)\n", st.removal().status().c_str(), st.removal().elapsed_s());
    std::fflush(stdout);
    phase_ = 2;
  }
  return host.settled();
}

void ScriptRunner::start_export(AppState& st, const ScriptAction& a) {
  if (a.what.empty()) {  // the button as the dialog stands
    st.start_export();
    return;
  }
  StudioSettings& set = st.settings();
  set.export_ply = a.what == "ply";
  set.export_baked = a.what == "baked";
  set.export_renders = a.what == "renders";
  const std::string path = fs::absolute(a.path).lexically_normal().string();  // scripts: from the current folder
  if (set.export_ply) set.export_ply_path = path;
  if (set.export_baked) {
    set.export_baked_path = path;
    if (a.count > 0) set.export_baked_iterations = a.count;
  }
  if (set.export_renders) {
    set.export_renders_dir = path;
    set.export_render_path = a.render_path;
    set.export_frames = a.count;
  }
  st.start_export();
}

ScriptRunner::JobLines ScriptRunner::export_lines(AppState& st, const ScriptAction& a) {
  ExportJob& job = st.exporter();
  JobLines j{"export", job};
  j.start = [&st, &a] { start_export(st, a); };
  j.cancel = [&job] { job.cancel(); };
  j.print_done = [&job] { std::printf("export: %s (%.1f s)\n", job.result().summary.c_str(), job.elapsed_s()); };
  return j;
}

ScriptRunner::JobLines ScriptRunner::import_lines(AppState& st, const ScriptAction& a) {
  CaptureJob& job = st.importer();
  JobLines j{"import", job};
  j.start = [&st, &a] { start_import(st, a); };
  j.cancel = [&job] { job.cancel(); };
  j.reported = [&st] { return st.import_reported(); };
  j.print_done = [&job] {
    std::printf("import: %s (%.1f s)\n%s", job.status().c_str(), job.elapsed_s(),
                capture::report_text(*job.report()).c_str());
  };
  j.print_refusal = true;
  return j;
}

bool ScriptRunner::run_job_line(ScriptHost& host, const ScriptAction& a, JobLine line, const JobLines& lines) {
  const std::string noun = lines.noun;
  if (line == JobLine::Start || (line == JobLine::Run && phase_ == 0)) {
    if (!host.settled()) return false;
    lines.start();
    phase_ = 1;
    return line == JobLine::Start;
  }
  if (phase_ == 0) {
    if (line == JobLine::Cancel) {
      if (!lines.job.active()) throw Error("no " + noun + " is running");
      lines.cancel();
    } else if (lines.job.state() == JobState::Idle) {
      throw Error("no " + noun + " was started");
    }
    phase_ = 1;
  }
  const JobState expect = line == JobLine::Cancel        ? JobState::Cancelled
                          : line == JobLine::ExpectError ? JobState::Error
                                                         : JobState::Done;
  if (phase_ == 1) {
    if (lines.job.active() || (lines.reported && !lines.reported())) return false;
    const JobState s = lines.job.state();
    if (s != expect) {
      fail(a, "the " + noun + " ended " + job_state_name(s) + " (expected " + job_state_name(expect) +
                  "): " + lines.job.status());
      return false;
    }
    if (s == JobState::Done) {
      lines.print_done();
      std::fflush(stdout);
    }
    phase_ = 2;
  }
  if (!host.settled()) return false;
  if (line != JobLine::ExpectError) return true;
  if (lines.job.status().find(a.text) == std::string::npos) {
    fail(a, "the " + noun + " failed with '" + lines.job.status() + "', which does not contain '" + a.text + "'");
    return false;
  }
  if (lines.print_refusal) {
    std::printf("%s refused: %s\n", lines.noun, lines.job.status().c_str());
    std::fflush(stdout);
  }
  return true;
}

}  // namespace goris::ui

namespace goris::ui {

void ScriptRunner::start_import(AppState& st, const ScriptAction& a) {
  capture::CaptureOptions& f = st.import_form;
  f = capture::CaptureOptions();
  f.input = fs::absolute(a.path).lexically_normal();  // scripts: from the current folder
  f.out = fs::absolute(a.out).lexically_normal();
  f.max_images = a.count;
  f.width = a.width;
  f.matcher = a.matcher;
  if (!a.masks.empty()) f.masks = fs::absolute(a.masks).lexically_normal();
  st.start_import(f);
}

bool ScriptRunner::imported_data_open(ScriptHost& host, const ScriptAction& a) {
  AppState& st = host.state();
  if (phase_ == 2) {
    if (st.opening()) return false;
    const fs::path out = st.importer().report()->out;
    if (!st.scene() || st.scene()->path != out) {
      fail(a, "the imported data set " + out.string() + " was not opened" +
                  (st.open_error().empty() ? std::string() : ": " + st.open_error()));
      return false;
    }
    std::printf("opened the imported data set %s (%zu training views)\n", out.string().c_str(),
                st.scene()->dataset ? st.scene()->dataset->train.size() : size_t(0));
    std::fflush(stdout);
    phase_ = 3;
  }
  return host.settled();
}

}  // namespace goris::ui
