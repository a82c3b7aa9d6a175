// AppState's selection tool actions (ui/document/app_state.h): the mouse, the panel and scripts all come here.
#include "core/io/output_path.h"
#include "core/util/error.h"
#include "ui/document/app_state.h"

namespace goris::ui {

namespace fs = std::filesystem;

ScreenRegion AppState::screen_region(ScreenRegion::Kind kind, glm::vec2 display, const char* what) const {
  require_selectable(what);
  if (!frame) throw Error(std::string(what) + ": no rendered view yet (open a run, or train a data set)");
  if (!(display.x > 0 && display.y > 0)) throw Error(std::string(what) + ": the main viewport shows no image");
  ScreenRegion r;
  r.kind = kind;
  r.camera = frame->camera;
  r.through = tools.through_all ? Through::All : Through::Visible;
  return r;
}

namespace {
glm::vec2 to_frame(const DisplayFrame& f, glm::vec2 p, glm::vec2 display) {
  return {p.x * float(f.width) / display.x, p.y * float(f.height) / display.y};
}
}  // namespace

std::uint64_t AppState::select_rect(glm::vec2 a, glm::vec2 b, glm::vec2 display, SelectMode mode) {
  ScreenRegion r = screen_region(ScreenRegion::Kind::Rect, display, "select rect");
  r.points = {to_frame(*frame, a, display), to_frame(*frame, b, display)};
  return selection_.screen_region(std::move(r), mode);
}

std::uint64_t AppState::select_polygon(const std::vector<glm::vec2>& points, glm::vec2 display, SelectMode mode) {
  ScreenRegion r = screen_region(ScreenRegion::Kind::Polygon, display, "select polygon");
  if (points.size() < 3) throw Error("select polygon: a lasso needs at least three points");
  for (const glm::vec2& p : points) r.points.push_back(to_frame(*frame, p, display));
  return selection_.screen_region(std::move(r), mode);
}

std::uint64_t AppState::select_brush(const std::vector<glm::vec2>& stroke, float radius, glm::vec2 display,
                                     SelectMode mode) {
  ScreenRegion r = screen_region(ScreenRegion::Kind::Brush, display, "select brush");
  if (stroke.empty()) throw Error("select brush: the stroke has no points");
  if (!(radius > 0)) throw Error("select brush: the radius must be positive");
  for (const glm::vec2& p : stroke) r.points.push_back(to_frame(*frame, p, display));
  r.radius = radius * float(frame->width) / display.x;
  return selection_.screen_region(std::move(r), mode);
}

std::uint64_t AppState::select_volume(const VolumeRegion& volume, SelectMode mode) {
  require_selectable(volume.kind == VolumeRegion::Kind::Box ? "select box" : "select sphere");
  return selection_.volume(volume, mode);
}

std::uint64_t AppState::select_colour(glm::vec3 rgb, float distance, SelectMode mode) {
  require_selectable("select by colour");
  if (!(distance >= 0)) throw Error("select by colour: the distance must not be negative");
  return selection_.colour(rgb, distance, mode);
}

std::uint64_t AppState::select_invert() {
  require_selectable("invert");
  return selection_.invert();
}

std::uint64_t AppState::select_step(int rings) {
  require_selectable(rings > 0 ? "grow step" : "shrink step");
  return selection_.step(rings);
}

std::uint64_t AppState::hide_selected() {
  require_selectable("hide");
  return selection_.hide_selected();
}

std::uint64_t AppState::lock_selected() {
  require_selectable("lock");
  return selection_.lock_selected();
}

std::uint64_t AppState::unhide_all() {
  require_selectable("unhide");
  return selection_.unhide_all();
}

std::uint64_t AppState::unlock_all() {
  require_selectable("unlock");
  return selection_.unlock_all();
}

std::uint64_t AppState::use_as_target_masks(fs::path dir) {
  require_selectable("use as target masks");
  if (!scene_ || !scene_->dataset || scene_->dataset->train.empty())
    throw Error("use as target masks: no training views (the run's data set is not open)");
  const fs::path run = current_run();
  if (dir.empty()) {
    if (run.empty()) throw Error("use as target masks: the model has no run folder: give a folder");
    dir = run / "target_masks";
  }
  dir = fs::absolute(dir).lexically_normal();
  // Never into the data set: its own object masks have the same names.
  const fs::path data =
      scene_->kind == OpenedScene::Kind::Run ? fs::path(scene_->run_config->input.data) : scene_->path;
  check_output_dir(dir, OutputGuard{{fs::absolute(data)}, {}});
  return selection_.target_masks(scene_->dataset->train, dir);
}

void AppState::place_volumes_if_needed() {
  if (tools.volumes_placed || !scene_) return;
  // Where the user clicked last, else the surface in the middle of the view, else the scene's centre.
  glm::vec3 centre = scene_->center;
  std::optional<PickResult> middle;
  if (frame) middle = pick(*frame, 0.5f * float(frame->width), 0.5f * float(frame->height));
  if (last_pick && last_pick->hit)
    centre = last_pick->world;
  else if (middle && middle->hit)
    centre = middle->world;
  tools.place_volumes(centre, 0.1f * scene_->radius);
}

}  // namespace goris::ui
