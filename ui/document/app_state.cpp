#include "ui/document/app_state.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "core/compute/device.h"
#include "core/io/output_path.h"
#include "core/util/error.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"
#include "ui/document/panel_layout.h"
#include "ui/document/train_options.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* compare_mode_id(CompareMode m) {
  switch (m) {
    case CompareMode::Off:
      return "off";
    case CompareMode::SideBySide:
      return "side_by_side";
    case CompareMode::Slider:
      return "slider";
  }
  return "off";
}

std::optional<CompareMode> compare_mode_from_id(const std::string& id) {
  for (CompareMode m : {CompareMode::Off, CompareMode::SideBySide, CompareMode::Slider})
    if (id == compare_mode_id(m)) return m;
  return std::nullopt;
}

namespace {
// Window pixel (x, y) of an image shown at w x h -> continuous pixel coordinates of the frame.
glm::vec2 frame_coords(const DisplayFrame& f, float x, float y, float w, float h) {
  return {(x + 0.5f) * float(f.width) / w, (y + 0.5f) * float(f.height) / h};
}

// A remembered choice stays even when it cannot be shown now (the viewport says why until it can).
Channel shown_channel(const std::string& id) { return channel_from_id(id).value_or(Channel::Final); }
}  // namespace

AppState::AppState(StudioSettings& settings) : settings_(settings) {
  main_channel = shown_channel(settings.main_channel);
  for (const std::string& id : settings.grid_channels) {
    if (int(grid_channels.size()) == kMaxGrid) break;
    grid_channels.push_back(shown_channel(id));
  }
  compare = compare_mode_from_id(settings.compare_mode).value_or(CompareMode::Off);
}

AppState::~AppState() {
  if (pending_open_.valid()) pending_open_.wait();
}

void AppState::message(const std::string& text, bool error) {
  last_message_ = text;
  last_message_error_ = error;
  if (on_message) on_message(text, error);
}

void AppState::open(const fs::path& path) {
  if (opening()) throw Error(path.string(), "cannot open while " + opening_path_.string() + " is still opening");
  if (training_active()) throw Error(path.string(), "cannot open while training runs: stop the training first");
  if (removal_.active()) throw Error(path.string(), "cannot open while the removal runs: cancel it first");
  Device device = Device::CPU;
  try {
    device = resolve_device(train_device_choice(settings_));
  } catch (const Error&) {
    device = Device::CPU;  // "cuda" asked for but absent: still show the scene
  }
  open_error_.clear();
  opening_path_ = fs::absolute(path).lexically_normal();
  pending_open_ = std::async(std::launch::async, [p = opening_path_, device] { return open_scene(p, device); });
}

void AppState::finish_open() {
  try {
    OpenedScene s = pending_open_.get();
    scene_ = std::move(s);
    ++scene_version_;
  } catch (const std::exception& e) {
    open_error_ = e.what();
    message(std::string("cannot open: ") + e.what(), true);
    return;
  }
  settings_.add_recent(scene_->path.string());
  const bool keep_view = std::exchange(keep_view_on_open_, false);
  const OrbitCamera kept_orbit = orbit;
  const std::optional<Camera> kept_snap = snapped;
  const size_t kept_index = snapped_index;
  const bool kept_test = snapped_test;
  session_version_seen_ = session_.snapshot_version();
  run_folder = scene_->kind == OpenedScene::Kind::Run ? scene_->path : fs::path();
  frame.reset();
  last_pick.reset();
  model_from_session_ = false;
  show_model(scene_->model);
  find_removal_masks();
  orbit.set_world(scene_->up, scene_->center, scene_->radius);
  snapped.reset();
  if (keep_view) {
    orbit = kept_orbit;
    if (kept_snap) snap(kept_index, kept_test);
  } else if (scene_->dataset && !scene_->dataset->train.empty()) {
    snap(0, false);
  } else if (scene_->dataset && !scene_->dataset->test.empty()) {
    snap(0, true);
  }
  for (const std::string& w : scene_->warnings) message("warning: " + w, false);
  std::string text = std::string("opened ") + scene_kind_name(scene_->kind) + " " + scene_->path.string();
  if (scene_->dataset)
    text += " (" + scene_->dataset->format + ", " + std::to_string(scene_->dataset->train.size()) + " training / " +
            std::to_string(scene_->dataset->test.size()) + " test views)";
  if (scene_->model) text += ", " + std::to_string(scene_->model->count()) + " Gaussians from " + scene_->model_source;
  message(text);
}

void AppState::show_model(std::shared_ptr<const ModelSnapshot> m) {
  model_ = std::move(m);
  ++model_version_;
  // The selection belongs to this model: a new one starts empty (or with its run's saved selection).
  std::string source;
  if (model_from_session_ && model_)
    source = checkpoint_path(session_.run_dir(), model_->iteration()).string();
  else if (scene_)
    source = scene_->model_source;
  // A cleaned scene's selection.json records what was removed from its parent run: not this model's.
  const fs::path run = current_run();
  const bool cleaned_scene = !run.empty() && fs::exists(run / "report.json") && fs::is_directory(run / "inpaint_masks");
  selection_.bind(model_, run, source, !training_active() && !cleaned_scene);
}

bool AppState::training_active() const { return session_.active(); }

fs::path AppState::current_run() const {
  if (model_from_session_) return session_.run_dir();
  if (scene_ && scene_->kind == OpenedScene::Kind::Run) return run_folder.empty() ? scene_->path : run_folder;
  return {};
}

void AppState::find_removal_masks() {
  removal_masks_dir_.clear();
  removal_result_.clear();
  const fs::path run = current_run();
  if (run.empty()) return;
  // A cleaned scene is a run folder of its own once stage 2 has written its model.
  const fs::path cleaned = run / "removal";
  if (fs::exists(cleaned / "config.json") && (fs::exists(run_ply_path(cleaned)) || has_checkpoint_files(cleaned)))
    removal_result_ = cleaned;
  else if (is_cleaned_scene(run))
    removal_result_ = run;
  auto has_masks = [](const fs::path& d) {
    return fs::is_directory(d / "lighting_masks") || fs::is_directory(d / "inpaint_masks");
  };
  // The run's stage 2, or the cleaned scene itself when that is what is open.
  if (has_masks(run / "removal"))
    removal_masks_dir_ = run / "removal";
  else if (has_masks(run))
    removal_masks_dir_ = run;
}

void AppState::poll() {
  if (pending_open_.valid() && pending_open_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
    finish_open();
  const JobState s = session_.state();
  if (s != last_session_state_) {
    if (s == JobState::Done || s == JobState::Error) message(session_.status(), s == JobState::Error);
    last_session_state_ = s;
  }
  const std::uint64_t v = session_.snapshot_version();
  if (v > session_version_seen_) {
    session_version_seen_ = v;
    model_from_session_ = true;
    show_model(session_.snapshot());
  }
  for (const auto& [text, error] : selection_.take_messages()) message(text, error);
  two_click.sync(*this);
  const JobState rs = removal_.state();
  if (rs != last_removal_state_) {
    if (rs == JobState::Done || rs == JobState::Cancelled || rs == JobState::Error)
      message("removal " + std::string(job_state_name(rs)) + ": " + removal_.status(), rs == JobState::Error);
    last_removal_state_ = rs;
  }
  if (removal_.runs_ended() != removal_runs_seen_) {
    removal_runs_seen_ = removal_.runs_ended();
    find_removal_masks();
    if (removal_.state() == JobState::Done && !removal_result_.empty() && removal_result_ != current_run() &&
        !training_active() && !opening()) {
      // The result replaces the scene with the target in the viewports; before / after toggles back.
      keep_view_on_open_ = true;
      open(removal_result_);
      message("showing the cleaned scene " + removal_result_.string() + " (Display: before / after)");
    }
  }
  if (importer_.runs_ended() != import_runs_seen_ && !opening()) {
    import_runs_seen_ = importer_.runs_ended();
    const JobState js = importer_.state();
    message("import " + std::string(job_state_name(js)) + ": " + importer_.status(), js == JobState::Error);
    // The new data set replaces what is shown, ready to train (unless training or a removal holds the scene).
    if (js == JobState::Done && importer_.report()) {
      try {
        open(importer_.report()->out);
      } catch (const Error& e) {
        message(std::string("the imported data set is not opened: ") + e.what(), true);
      }
    }
  }
  if (exporter_.runs_ended() != export_runs_seen_) {
    export_runs_seen_ = exporter_.runs_ended();
    const JobState es = exporter_.state();
    message(std::string("export ") + job_state_name(es) + ": " + exporter_.status(), es == JobState::Error);
  }
}

void AppState::start_import(const capture::CaptureOptions& options) {
  const std::string what = "import " + options.input.string();
  if (options.input.empty()) throw Error("import: no photo folder or video given");
  if (options.out.empty()) throw Error(what, "no output folder given");
  if (opening()) throw Error(what, "cannot import while " + opening_path_.string() + " is opening");
  if (training_active()) throw Error(what, "cannot import while training runs: stop the training first");
  if (removal_.active()) throw Error(what, "cannot import while the removal runs: cancel it first");
  importer_.start(options);
  message("importing " + options.input.string() + " into " + options.out.string() + " (COLMAP on the CPU)");
}

void AppState::add_override(const std::string& key, const std::string& value) {
  TrainConfig probe = new_run_config(settings_, overrides_);
  apply_config_override(probe, key, value);  // throws for an unknown key or a bad value
  overrides_.emplace_back(key, value);
}

void AppState::show_before(bool before) {
  if (before && !has_before())
    throw Error("before / after: the shown scene is not a cleaned scene (RUN/removal) whose run is there");
  if (showing_before() == before) return;
  show_model(before ? scene_->before_model : scene_->model);
}

void AppState::drop_override(const std::string& key) {
  std::erase_if(overrides_, [&](const auto& kv) { return kv.first == key; });
}

void AppState::start_training(int iterations, bool more) {
  if (!scene_) throw Error("train: open a data set or a run folder first");
  if (scene_->kind == OpenedScene::Kind::Model)
    throw Error(scene_->path.string(), "train: a model file has no photos to train on: open its data set or run folder");
  if (removal_.active()) throw Error("train: the removal is running on this run: wait for it or cancel it");
  TrainRequest rq;
  rq.iterations = iterations;
  rq.more = more;
  rq.config = new_run_config(settings_, overrides_);
  if (scene_->kind == OpenedScene::Kind::Run) {
    rq.run_dir = run_folder.empty() ? scene_->path : run_folder;
    rq.data = scene_->run_config->input.data;
  } else {
    if (run_folder.empty()) run_folder = default_run_folder(scene_->path);
    rq.run_dir = run_folder;
    rq.data = scene_->path;
    // The CLI's rules (goris train): a new run never goes into a data set, and a folder that already holds
    // another run is not silently resumed with that run's settings instead of these.
    const bool this_sessions_run = fs::absolute(rq.run_dir) == session_.run_dir();
    if (!this_sessions_run && (fs::exists(run_config_path(rq.run_dir)) || latest_checkpoint(rq.run_dir)))
      throw Error(rq.run_dir.string(), "already holds a training run: open that run to continue it, or choose another "
                                       "output folder");
    check_output_dir(rq.run_dir, OutputGuard{{rq.data}, {}});
  }
  session_.start(rq);
  message("training into " + rq.run_dir.string());
}

void AppState::snap(size_t index, bool test) {
  if (!scene_ || !scene_->dataset) throw Error("snap: no data set cameras (open a data set or a run with its data)");
  const std::vector<View>& views = test ? scene_->dataset->test : scene_->dataset->train;
  if (index >= views.size())
    throw Error("snap: there is no " + std::string(test ? "test" : "training") + " camera " + std::to_string(index) +
                " (" + std::to_string(views.size()) + " cameras)");
  snapped = views[index].camera;
  snapped_name = std::string(test ? "test " : "train ") + std::to_string(index) + " (" + views[index].name + ")";
  snapped_index = index;
  snapped_test = test;
  snapped_view = views[index].name;
  orbit.snap_to(*snapped);
}

Camera AppState::render_camera(float box_w, float box_h) const {
  int w = 1, h = 1;
  if (snapped) {
    const Rect fit = fit_aspect({0, 0, box_w, box_h}, float(snapped->width) / float(snapped->height));
    capped_size(fit.w, fit.h, settings_.display_max_side, w, h);
    return snapped->resized(w, h);
  }
  capped_size(box_w, box_h, settings_.display_max_side, w, h);
  return orbit.camera(w, h);
}

ChannelContext AppState::channel_context() const {
  ChannelContext c;
  c.intrinsic = model_ && model_->intrinsic();
  c.screen_filter = c.intrinsic && model_->shading()->config.intrinsic.screen_space_filter;
  c.removal_masks = !removal_masks_dir_.empty();
  c.snapped_training = snapped.has_value() && !snapped_test;
  return c;
}

void AppState::set_channel(int viewport, Channel c) {
  const ChannelInfo& info = channel_info(c);
  if (const char* why = channel_unavailable(c)) throw Error(std::string("channel ") + info.id + ": " + why);
  if (viewport < 0) {
    main_channel = c;
    settings_.main_channel = info.id;
    return;
  }
  if (viewport >= int(grid_channels.size()))
    throw Error("channel: there is no grid viewport " + std::to_string(viewport) + " (the grid has " +
                std::to_string(grid_channels.size()) + ")");
  grid_channels[size_t(viewport)] = c;
  settings_.grid_channels[size_t(viewport)] = info.id;
}

void AppState::set_grid_count(int n) {
  n = n < 0 ? 0 : n > kMaxGrid ? kMaxGrid : n;
  static constexpr Channel kDefaults[] = {Channel::Diffuse, Channel::Normal, Channel::Depth, Channel::Roughness,
                                          Channel::Fresnel, Channel::Region, Channel::Label, Channel::Alpha};
  while (int(grid_channels.size()) < n) grid_channels.push_back(kDefaults[grid_channels.size()]);
  grid_channels.resize(size_t(n));
  settings_.grid_channels.clear();
  for (Channel c : grid_channels) settings_.grid_channels.push_back(channel_info(c).id);
}

void AppState::set_compare(CompareMode m, float split) {
  compare = m;
  compare_split = split < 0 ? 0 : split > 1 ? 1 : split;
  settings_.compare_mode = compare_mode_id(m);
}

PickResult AppState::click(float x, float y, float display_w, float display_h) {
  if (!frame) throw Error("click: no rendered view yet (open a run, or train a data set)");
  if (!(display_w > 0 && display_h > 0) || x < 0 || y < 0 || x >= display_w || y >= display_h)
    throw Error("click: (" + std::to_string(x) + ", " + std::to_string(y) + ") lies outside the main viewport's " +
                std::to_string(int(display_w)) + "x" + std::to_string(int(display_h)) + " image");
  const glm::vec2 uv = frame_coords(*frame, x, y, display_w, display_h);
  const std::optional<PickResult> r = pick(*frame, uv.x, uv.y);
  if (!r) throw Error("click: outside the rendered image");
  last_pick = r;
  char text[200];
  if (r->hit)
    std::snprintf(text, sizeof text, "picked pixel (%d, %d): depth %.4g, opacity %.2f, world (%.4g, %.4g, %.4g)", r->x,
                  r->y, double(r->depth), double(r->alpha), double(r->world.x), double(r->world.y), double(r->world.z));
  else
    std::snprintf(text, sizeof text, "picked pixel (%d, %d): nothing there (opacity %.2f)", r->x, r->y,
                  double(r->alpha));
  message(text);
  return *r;
}

const char* AppState::selection_blocked() const {
  if (!model_) return "nothing to select in (open a run, or train a model first)";
  if (training_active()) return "the model changes while it trains: stop the training first";
  if (removal_.active()) return "the removal is running: wait for it or cancel it";
  return nullptr;
}

void AppState::require_selectable(const char* what) const {
  if (const char* why = selection_blocked()) throw Error(std::string(what) + ": " + why);
}

std::uint64_t AppState::mouse_click(float x, float y, float display_w, float display_h, SelectMode mode) {
  click(x, y, display_w, display_h);
  if (const char* why = selection_blocked()) {
    message(std::string("not selected: ") + why);
    return 0;
  }
  const glm::vec2 uv = frame_coords(*frame, x, y, display_w, display_h);
  return selection_.click(frame->camera, uv.x, uv.y, mode);
}

std::uint64_t AppState::select_click(float x, float y, float display_w, float display_h, SelectMode mode) {
  require_selectable("select");
  return mouse_click(x, y, display_w, display_h, mode);
}

std::uint64_t AppState::select_grow(float grow, bool merge) {
  require_selectable("grow");
  if (!(grow >= -1.0f && grow <= 1.0f))
    throw Error("grow: " + std::to_string(grow) + " is outside -1..1 (negative values shrink)");
  return selection_.set_grow(grow, merge);
}

std::uint64_t AppState::select_labels() {
  require_selectable("select by label");
  return selection_.from_labels();
}

std::uint64_t AppState::select_masks() {
  require_selectable("select by masks");
  if (!scene_ || !scene_->dataset || scene_->dataset->train.empty())
    throw Error("select by masks: no training views with masks (the run's data set is not open)");
  return selection_.from_masks(scene_->dataset->train);
}

std::uint64_t AppState::select_clear() {
  require_selectable("clear selection");
  return selection_.clear();
}

std::uint64_t AppState::undo_selection() {
  require_selectable("undo");
  return selection_.undo();
}

std::uint64_t AppState::redo_selection() {
  require_selectable("redo");
  return selection_.redo();
}

fs::path AppState::save_selection() {
  require_selectable("save selection");
  return selection_.save();
}

void AppState::start_removal(int iterations) {
  const fs::path run = current_run();
  if (run.empty() && scene_ && scene_->kind == OpenedScene::Kind::Model)
    throw Error(scene_->path.string(), "remove: a model file has no photos to fill the hole from: open the run "
                                       "folder it was trained in");
  if (run.empty()) throw Error("remove: no run to remove from (train a model, or open a run folder)");
  if (training_active()) throw Error("remove: training runs on this run: stop it first");
  if (!latest_checkpoint(run)) throw Error(run.string(), "remove: the run has no checkpoint yet (train it first)");
  if (selection_.busy()) throw Error("remove: wait until the selection edit is done");
  const SelectionView sel = selection_.view();
  if (sel.mask && !sel.saved) save_selection();  // the removal takes RUN/selection.json: what is shown
  RemovalOptions o;
  if (!settings_.removal_inpainter.empty()) o.inpainter = settings_.removal_inpainter;
  o.finetune_iterations = iterations > 0 ? iterations : settings_.removal_iterations;
  if (settings_.removal_ablate_material) o.ablate.insert("material");
  if (settings_.removal_ablate_lamask) o.ablate.insert("lamask");
  if (settings_.removal_ablate_twins) o.ablate.insert("twins");
  if (settings_.removal_ablate_shadows) o.ablate.insert("shadows");
  o.lighting_relative_fresnel = !settings_.removal_absolute_fresnel;
  o.dereflect_lighting = !settings_.removal_exclude_reflections;
  o.device = train_device_choice(settings_);
  removal_.start(run, o);
  message("removing in " + (run / "removal").string() +
          (sel.mask ? " (the selection: " + std::to_string(sel.selected) + " Gaussians)"
                    : " (no selection: RUN/selection.json or the learned labels)"));
}

fs::path AppState::export_source() const {
  if (export_from_removal && !removal_result_.empty()) return removal_result_;
  return current_run();
}

ExportRequest AppState::export_request() const {
  const StudioSettings& s = settings_;
  ExportRequest r;
  r.run_dir = export_source();
  // Relative choices lie inside the exported run folder, so each run keeps its own exports.
  auto place = [&](bool wanted, const std::string& path, const char* what) -> fs::path {
    if (!wanted) return {};
    if (path.empty()) throw Error(std::string("export: the ") + what + " is chosen but its path is empty");
    const fs::path p(path);
    return p.is_absolute() ? p : r.run_dir / p;
  };
  r.ply = place(s.export_ply, s.export_ply_path, "intrinsic PLY");
  r.baked = place(s.export_baked, s.export_baked_path, "baked PLY");
  r.renders = place(s.export_renders, s.export_renders_dir, "renders folder");
  r.baked_iterations = s.export_baked_iterations;
  if (!r.baked.empty()) {
    if (s.export_baked_spz) r.baked_formats.push_back(SplatFormat::Spz);
    if (s.export_baked_compressed_ply) r.baked_formats.push_back(SplatFormat::CompressedPly);
    if (s.export_baked_splat) r.baked_formats.push_back(SplatFormat::Antimatter);
    if (s.export_baked_glb) r.baked_formats.push_back(SplatFormat::Glb);
  }
  r.render_path = parse_render_path(s.export_render_path);
  r.frames = s.export_frames;
  r.device = train_device_choice(s);
  return r;
}

void AppState::start_export() {
  if (export_source().empty()) throw Error("export: no run to export (train a model, or open a run folder)");
  if (training_active())
    throw Error("export: the model changes while it trains: stop the training first (the export reads the run's "
                "latest checkpoint)");
  if (removal_.active() && export_source() == removal_result_)
    throw Error("export: the removal is still writing the cleaned scene: wait for it or cancel it");
  const ExportRequest r = export_request();
  exporter_.start(r);
  export_runs_seen_ = exporter_.runs_ended();
  message("exporting " + r.run_dir.string());
}

}  // namespace goris::ui
