#include "ui/selection/selection_session.h"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "removal/selection/selection_file.h"
#include "removal/selection/selection_labels.h"
#include "removal/selection/selection_masks.h"
#include "ui/display/background_priority.h"
#include "ui/selection/session_context.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

std::string count_text(std::size_t selected, std::size_t total) {
  char b[96];
  std::snprintf(b, sizeof b, "%zu of %zu Gaussians selected (%.1f%%)", selected, total,
                total ? 100.0 * double(selected) / double(total) : 0.0);
  return b;
}

}  // namespace

SelectionSession::SelectionSession() : thread_([this] { loop(); }) {}

SelectionSession::~SelectionSession() {
  {
    std::lock_guard lk(mutex_);
    quit_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  thread_.join();
}

void SelectionSession::message(const std::string& text, bool error) {
  std::lock_guard lk(mutex_);
  messages_.emplace_back(text, error);
}

std::vector<std::pair<std::string, bool>> SelectionSession::take_messages() {
  std::lock_guard lk(mutex_);
  return std::exchange(messages_, {});
}

void SelectionSession::bind(std::shared_ptr<const ModelSnapshot> model, const fs::path& run_dir,
                            const std::string& model_source, bool load_saved) {
  {
    std::lock_guard lk(mutex_);
    run_dir_ = run_dir;
    model_source_ = model_source;
    if (model == model_) return;
    ++generation_;
    for (const Job& j : queue_) results_[j.id] = "the model changed before this edit ran";
    queue_.clear();
    model_ = std::move(model);
    history_.reset({});
    saved_mask_.reset();
    ++version_;
  }
  if (!load_saved || !model_ || run_dir.empty() || !fs::exists(selection_json_path(run_dir))) return;
  submit([this, run_dir](const Job& job) {
    // A selection saved for this very model is the starting point (not undoable); a stale one is reported.
    StoredSelection stored;
    try {
      stored = read_selection(run_dir, job.model->to_model());
    } catch (const Error& e) {
      message(std::string("not loaded: ") + e.what(), false);
      return;
    }
    SelectionState s;
    s.selected = count_selected(stored.mask);
    SelectionPart part;
    part.seeds = stored.mask;
    part.method = "saved";
    part.what = "saved selection (" + stored.record.method + ")";
    s.parts.push_back(std::move(part));
    if (s.selected > 0) s.mask = std::make_shared<const SelectionMask>(std::move(stored.mask));
    {
      std::lock_guard lk(mutex_);
      if (job.generation != generation_) return;
      history_.reset(s);
      saved_mask_ = s.mask;
      ++version_;
    }
    message("loaded " + selection_json_path(run_dir).string() + ": " + count_text(s.selected, job.model->count()),
            false);
  });
}

std::uint64_t SelectionSession::submit(std::function<void(const Job&)> run, bool merge) {
  std::lock_guard lk(mutex_);
  Job j;
  j.id = next_id_++;
  j.generation = generation_;
  j.model = model_;
  j.run = std::move(run);
  j.merge = merge;
  // Slider edits queued behind each other: only the newest needs to run.
  if (merge && !queue_.empty() && queue_.back().merge) {
    results_[queue_.back().id] = "";
    queue_.pop_back();
  }
  const std::uint64_t id = j.id;
  queue_.push_back(std::move(j));
  wake_.notify_all();
  return id;
}

SelectionSession::Context& SelectionSession::prepared(const std::shared_ptr<const ModelSnapshot>& model) {
  if (!context_ || context_->model != model) {
    context_.reset();
    auto c = std::make_unique<Context>();
    const GaussianModel m = model->to_model();
    c->selection.points = selection_points(m);
    c->selection.graph = build_selection_graph(c->selection.points);
    c->picker = std::make_unique<GaussianPicker>(m);
    c->model = model;
    context_ = std::move(c);
  }
  return *context_;
}

SelectionState SelectionSession::current_state() const {
  std::lock_guard lk(mutex_);
  return history_.current();
}

void SelectionSession::push_state(const Job& job, std::vector<SelectionPart> parts, float grow,
                                  const std::string& done, std::optional<SelectionGuard> guard) {
  if (!guard) guard = current_state().guard;
  SelectionState s = evaluate_selection(prepared(job.model).selection, std::move(parts), grow, std::move(*guard));
  const std::string text = done + (done.empty() ? "" : ": ") + count_text(s.selected, job.model->count());
  {
    std::lock_guard lk(mutex_);
    if (job.generation != generation_) return;
    history_.push(std::move(s), job.merge);
    ++version_;
  }
  message(text, false);
}

std::uint64_t SelectionSession::click(const Camera& camera, float u, float v, SelectMode mode) {
  return submit([this, camera, u, v, mode](const Job& job) {
    Context& c = prepared(job.model);
    const goris::PickResult p = c.shown_picker(current_state().guard.hidden).pick(camera, u, v);
    if (!p.hit) {
      char b[160];
      std::snprintf(b, sizeof b,
                    "select: nothing there at (%.0f, %.0f) (the ray's opacity is %.2f): click on the object", u, v,
                    double(p.ray_alpha));
      throw Error(b);
    }
    SelectionPart part;
    part.mode = mode;
    part.seeds.assign(job.model->count(), 0);
    part.seeds[p.gaussian] = 1;
    part.grows = true;
    part.method = "click";
    char what[96];
    std::snprintf(what, sizeof what, "click at (%d, %d)", int(u), int(v));
    part.what = what;
    SelectionState cur = current_state();
    cur.parts.push_back(std::move(part));
    char done[160];
    std::snprintf(done, sizeof done, "picked Gaussian %u (weight %.2f, depth %.3g), %s", p.gaussian,
                  double(p.weight), double(p.depth), select_mode_id(mode));
    push_state(job, std::move(cur.parts), cur.grow, done);
  });
}

std::uint64_t SelectionSession::set_grow(float grow, bool merge) {
  return submit(
      [this, grow](const Job& job) {
        SelectionState cur = current_state();
        char done[64];
        std::snprintf(done, sizeof done, "grow %.2f", double(grow));
        push_state(job, std::move(cur.parts), grow, done);
      },
      merge);
}

std::uint64_t SelectionSession::from_labels(float threshold) {
  return submit([this, threshold](const Job& job) {
    Context& c = prepared(job.model);
    LabelSelectSettings ls;
    ls.threshold = threshold;
    const SelectionResult r = select_by_label(c.selection.points, ls);
    if (r.summary.seeds == 0) {
      float max_label = 0;
      for (float l : c.selection.points.label) max_label = std::max(max_label, l);
      char b[256];
      std::snprintf(b, sizeof b,
                    "select by label: no Gaussian has a label above %.2f (the largest is %.3f): train in intrinsic "
                    "mode on a data set with object masks, or select with masks or clicks",
                    double(threshold), double(max_label));
      throw Error(b);
    }
    SelectionPart part;
    part.seeds = r.mask;
    part.method = "labels";
    char what[64];
    std::snprintf(what, sizeof what, "labels > %.2f", double(threshold));
    part.what = what;
    push_state(job, {std::move(part)}, current_state().grow, r.summary.describe(std::string("by ") + what));
  });
}

std::uint64_t SelectionSession::from_masks(std::vector<View> views, std::optional<fs::path> dir) {
  return submit([this, views = std::move(views), dir](const Job& job) {
    Context& c = prepared(job.model);
    const std::vector<MaskedView> masked = load_masked_views(views, dir);
    const MaskVotes votes = labels_from_masks(job.model->to_model(), masked, {}, job.model->settings());
    const SelectionResult r = close_selection(c.selection.points, votes.selected);
    if (r.summary.seeds == 0)
      throw Error("select by masks: no Gaussian falls inside the object masks in at least half of the views where "
                  "it is visible (are the masks white on the object?)");
    SelectionPart part;
    part.seeds = r.mask;
    part.method = "masks";
    part.what = "object masks of " + std::to_string(masked.size()) + " views" + (dir ? " in " + dir->string() : "");
    push_state(job, {std::move(part)}, current_state().grow, r.summary.describe("by mask votes"));
  });
}

std::uint64_t SelectionSession::clear() {
  return submit([this](const Job& job) { push_state(job, {}, current_state().grow, "cleared"); });
}

std::uint64_t SelectionSession::undo() { return step_history(false); }
std::uint64_t SelectionSession::redo() { return step_history(true); }

std::uint64_t SelectionSession::step_history(bool forward) {
  return submit([this, forward](const Job& job) {
    const char* what = forward ? "redo" : "undo";
    bool moved = false;
    std::size_t n = 0;
    {
      std::lock_guard lk(mutex_);
      if (job.generation != generation_) return;
      moved = forward ? history_.redo() : history_.undo();
      n = history_.current().selected;
      if (moved) ++version_;
    }
    if (!moved) throw Error(std::string(what) + ": nothing to " + what);
    message(std::string(what) + ": " + count_text(n, job.model->count()), false);
  });
}

fs::path SelectionSession::save() {
  std::shared_ptr<const ModelSnapshot> model;
  fs::path run;
  std::string source;
  SelectionState s;
  {
    std::lock_guard lk(mutex_);
    if (running_job_ || !queue_.empty()) throw Error("save selection: wait until the selection edit is done");
    model = model_;
    run = run_dir_;
    source = model_source_;
    s = history_.current();
  }
  if (!model) throw Error("save selection: no model is shown");
  if (run.empty()) throw Error("save selection: the model has no run folder (train it, or open a run)");
  if (!s.mask) throw Error("save selection: nothing is selected");

  SelectionRecord record;
  bool all_clicks = !s.parts.empty();
  for (const SelectionPart& p : s.parts) all_clicks &= p.method == "click";
  record.method = all_clicks ? "click" : s.parts.size() == 1 ? s.parts[0].method : "edited";
  nlohmann::json parts = nlohmann::json::array();
  for (const SelectionPart& p : s.parts)
    parts.push_back({{"mode", select_mode_id(p.mode)}, {"method", p.method}, {"what", p.what}});
  record.parameters = {{"grow", s.grow}, {"parts", parts}, {"editor", "goris-studio"}};
  record.summary = {{"total", model->count()}, {"selected", s.selected}};
  std::error_code ec;
  const fs::path rel = fs::relative(source, run, ec);
  record.model_source = !ec && !rel.empty() && rel.native()[0] != '.' ? rel.string() : source;
  const GaussianModel m = model->to_model();
  record.model_fingerprint = model_fingerprint(m);
  const fs::path json = selection_json_path(run);
  write_selection(json, record, *s.mask);
  {
    std::lock_guard lk(mutex_);
    if (history_.current().mask == s.mask) saved_mask_ = s.mask;
    ++version_;
  }
  message("saved " + json.string() + ": " + count_text(s.selected, model->count()), false);
  return json;
}

bool SelectionSession::busy() const {
  std::lock_guard lk(mutex_);
  return running_job_ || !queue_.empty();
}

bool SelectionSession::finished(std::uint64_t job) const {
  std::lock_guard lk(mutex_);
  return results_.count(job) > 0;
}

std::optional<std::string> SelectionSession::job_error(std::uint64_t job) const {
  std::lock_guard lk(mutex_);
  const auto it = results_.find(job);
  if (it == results_.end() || it->second.empty()) return std::nullopt;
  return it->second;
}

std::uint64_t SelectionSession::version() const {
  std::lock_guard lk(mutex_);
  return version_;
}

SelectionView SelectionSession::view() const {
  std::lock_guard lk(mutex_);
  const SelectionState& s = history_.current();
  SelectionView v;
  v.mask = s.mask;
  v.selected = s.selected;
  v.total = model_ ? model_->count() : 0;
  v.grow = s.grow;
  for (const SelectionPart& p : s.parts)
    v.parts.push_back((p.mode == SelectMode::Add ? "+ " : p.mode == SelectMode::Remove ? "- " : "") + p.what);
  v.can_undo = history_.can_undo();
  v.can_redo = history_.can_redo();
  v.saved = s.mask && s.mask == saved_mask_;
  v.hidden = s.guard.hidden;
  v.hidden_count = s.guard.hidden_count;
  v.locked_count = s.guard.locked_count;
  return v;
}

void SelectionSession::loop() {
  const BackgroundPriority background;  // the GUI thread goes first
  for (;;) {
    Job job;
    {
      std::unique_lock lk(mutex_);
      wake_.wait(lk, [&] { return quit_ || !queue_.empty(); });
      if (quit_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      running_job_ = true;
    }
    std::string error;
    try {
      if (!job.model) throw Error("selection: nothing to select in (open a run, or train a model first)");
      job.run(job);
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (!error.empty()) message(error, true);
    std::lock_guard lk(mutex_);
    running_job_ = false;
    results_[job.id] = error;
    while (results_.size() > 256) results_.erase(results_.begin());
  }
}

}  // namespace goris::ui
