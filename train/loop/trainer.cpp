#include "train/loop/trainer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <optional>
#include <utility>

#include "core/compute/finite_check.h"
#include "core/compute/memory.h"
#include "core/io/file_bytes.h"
#include "core/scene/filter3d.h"
#include "core/util/error.h"
#include "train/loop/checkpoint.h"
#include "train/optimizer/lr_schedule.h"
#include "train/optimizer/param_groups.h"

namespace goris {

namespace {

constexpr ParamGroup kRadianceGroups[] = {ParamGroup::Position, ParamGroup::Scale,   ParamGroup::Rotation,
                                          ParamGroup::Opacity,  ParamGroup::ShDc,    ParamGroup::ShRest};

// Every loss term of a step by name (for messages about a bad step).
std::array<std::pair<const char*, double>, 11> loss_term_list(const StepStats& s) {
  return {{{"l1", s.l1}, {"ssim", s.ssim}, {"alpha", s.alpha}, {"depth_normal", s.depth_normal}, {"distortion", s.distortion},
           {"normal_prior", s.normal_prior},
           {"smoothness", s.smoothness}, {"region", s.region}, {"label", s.label}, {"appearance", s.appearance},
           {"material", s.material}}};
}

std::string loss_terms(const StepStats& s) {
  std::string out;
  for (const auto& [name, v] : loss_term_list(s)) out += (out.empty() ? "" : ", ") + std::string(name) + "=" + std::to_string(v);
  return out;
}

// The loss terms that are not finite, by name.
std::string non_finite_terms(const StepStats& s) {
  std::string out;
  for (const auto& [name, v] : loss_term_list(s))
    if (!std::isfinite(v)) out += (out.empty() ? "term " : ", ") + std::string(name) + "=" + std::to_string(v);
  return out.empty() ? "total " + std::to_string(s.loss) : out;
}

std::string format_iteration_problem(int it, const std::string& what) {
  return "iteration " + std::to_string(it) + ": " + what;
}

}  // namespace

Trainer::Trainer(TrainConfig config, std::vector<TrainView> views, float extent,
                 std::shared_ptr<DifferentiableRenderer> renderer, TrainerState state)
    : config_(std::move(config)),
      views_(std::move(views)),
      extent_(extent),
      renderer_(std::move(renderer)),
      device_(renderer_ ? renderer_->device() : Device::CPU),
      state_(std::move(state)) {
  if (!renderer_) throw Error("training: no renderer");
  config_.validate("training configuration");
  if (config_.mode == TrainMode::Auto) throw Error("training: mode 'auto' must be resolved from the data set before training");
  if (views_.empty()) throw Error("training: no training views");
  for (const TrainView& v : views_)
    if (v.image.size() != size_t(3) * v.camera.width * v.camera.height)
      throw Error(v.name, "training image size does not match its camera");
  if (!(extent_ > 0) || !std::isfinite(extent_)) throw Error("training: the scene extent must be positive");
  if (state_.model.device() != device_) throw Error("training: the model lives on another device");
  if (state_.model.count() == 0) throw Error("training: the initial model has no Gaussians");
  state_.model.max_sh_degree = config_.sh.max_degree;
  for (const std::uint32_t v : state_.view_stack)
    if (v >= views_.size()) throw Error("training: the saved view order refers to a view that does not exist");
  if (state_.stats.grad_accum.size() != state_.model.count()) state_.stats.reset(state_.model.count(), device_);
  if (config_.anti_aliasing.filter_3d && state_.model.filter3d_var.size() != state_.model.count())
    compute_filter3d(state_.model, cameras());
  make_hooks();
}

TrainerState Trainer::initial_state(const TrainConfig& config, GaussianModel model) {
  TrainerState s;
  s.model = std::move(model);
  s.model.sh_degree = 0;
  s.model.max_sh_degree = config.sh.max_degree;
  s.rng.seed(config.seed);
  return s;
}

void Trainer::make_hooks() {
  hooks_ = make_train_hooks(config_, *renderer_);
  for (const auto& h : hooks_)
    if (const auto saved = state_.hooks.find(h->name()); saved != state_.hooks.end())
      h->deserialize(saved->second, "training state of hook '" + std::string(h->name()) + "'");
}

void Trainer::store_hook_states() {
  for (const auto& h : hooks_) {
    std::string bytes = h->serialize();
    if (bytes.empty())
      state_.hooks.erase(h->name());
    else
      state_.hooks[h->name()] = std::move(bytes);
  }
}

void Trainer::switch_mode(TrainConfig config, std::shared_ptr<DifferentiableRenderer> renderer,
                          const std::function<void(std::vector<TrainView>&)>& update_views) {
  if (!renderer) throw Error("training: no renderer");
  if (renderer->device() != device_) throw Error("training: the new renderer lives on another device");
  config.validate("training configuration");
  if (config.mode == TrainMode::Auto) throw Error("training: mode 'auto' must be resolved before switching to it");
  const std::vector<ParamGroup> before = active_groups();
  const size_t n_views = views_.size();
  config_ = std::move(config);
  renderer_ = std::move(renderer);
  store_hook_states();  // the new configuration's hooks continue from them, as after a resume
  make_hooks();
  state_.model.max_sh_degree = config_.sh.max_degree;
  if (update_views) update_views(views_);
  if (views_.size() != n_views) throw Error("training: switching modes must keep the training views");
  for (const TrainView& v : views_) {
    const size_t hw = size_t(v.camera.width) * size_t(v.camera.height);
    if (!v.glossy_mask.empty() && v.glossy_mask.size() != hw) throw Error(v.name, "glossy mask size does not match its camera");
    if (!v.normal_prior.empty() && v.normal_prior.size() != 3 * hw) throw Error(v.name, "normal prior size does not match its camera");
  }
  for (ParamGroup g : active_groups())
    if (std::find(before.begin(), before.end(), g) == before.end()) {
      reset_moments(state_.model, g);
      state_.adam.steps[size_t(g)] = 0;
    }
}

std::vector<const std::vector<float>*> glossy_masks_of(const std::vector<TrainView>& views) {
  std::vector<const std::vector<float>*> masks;
  masks.reserve(views.size());
  for (const TrainView& v : views) masks.push_back(v.glossy_mask.empty() ? nullptr : &v.glossy_mask);
  return masks;
}

std::vector<Camera> cameras_of(const std::vector<TrainView>& views) {
  std::vector<Camera> c;
  c.reserve(views.size());
  for (const TrainView& v : views) c.push_back(v.camera);
  return c;
}

std::vector<Camera> Trainer::cameras() const { return cameras_of(views_); }

StepStats Trainer::step() {
  if (finished()) throw Error("training: step() called after the last iteration");
  const int it = state_.iteration + 1;
  GaussianModel& m = state_.model;
  StepStats out;
  if (it % config_.sh.degree_interval == 0) m.sh_degree = std::min(m.sh_degree + 1, m.max_sh_degree);
  const TrainView& view = next_view(out);
  const Camera& cam = view.camera;
  HookStep hook{it, config_, m, views_, view, *renderer_, extent_, out};
  hook.model_pruned = [this] { model_changed(); };

  // Render.
  const bool with_extras = renderer_->wants_extras();
  renderer_->begin_iteration(it);
  for (const auto& h : hooks_) h->before_forward(hook);
  const GaussianView gv = m.view(with_extras);
  const RenderedImages fwd = renderer_->forward(gv, cam);
  if (fwd.width != cam.width || fwd.height != cam.height) throw Error("training: the renderer returned an image of another size");

  // Losses and their image gradients; a non-finite loss skips the step, naming the terms (checked again
  // after the hooks' passes, which may add loss).
  LossGradients g = losses(view, fwd, it, out);
  const auto loss_not_finite = [&] {
    if (std::isfinite(out.loss)) return false;
    skip_step(it, "the loss is not finite (" + non_finite_terms(out) + ") on view " + view.name, out);
    return true;
  };
  if (loss_not_finite()) return out;

  // Backward.
  const GaussianGradView gg = backward(gv, g, with_extras);
  hook.gaussians = &gv;
  hook.grads = &gg;
  for (const auto& h : hooks_) h->after_backward(hook);
  if (loss_not_finite()) return out;
  if (with_extras) m.backprop_extras();
  if (it <= densify_until())
    state_.stats.add_view(view_grad_norm_.data(), fwd.radii, ndc_gradient_scale(cam.width, cam.height), m.count(), device_);
  if (const std::string bad = non_finite_gradient(); !bad.empty()) {
    skip_step(it, "non-finite gradient in " + bad + " on view " + view.name + " (loss terms: " + loss_terms(out) + ")", out);
    return out;
  }
  consecutive_skips_ = 0;

  // Optimiser step, density control, and the hooks that act on the updated model.
  optimizer_step(it);
  out.densify = densify(it);
  if (out.densify.after > 0) {
    const DensifyCounts& c = out.densify;
    hook.note("density control: " + std::to_string(c.before) + " -> " + std::to_string(c.after) + " Gaussians (" +
              std::to_string(c.cloned) + " cloned, " + std::to_string(c.split) + " split, " +
              std::to_string(c.pruned) + " pruned)");
  }
  for (const auto& h : hooks_) h->after_densify(hook);

  // D is the SH colour; the diffuse channel shows its view-independent part (maps, editor, PLY), in both
  // modes, so that a radiance run's PLY opens with colours in the editor's diffuse viewport too.
  m.derive_diffuse_from_sh();

  // Smoothed over about the last 20 iterations (views differ a lot in difficulty).
  state_.ema_loss = state_.iteration == 0 ? out.loss : 0.05 * out.loss + 0.95 * state_.ema_loss;
  const double psnr = std::min(out.psnr, 99.0);
  state_.ema_psnr = state_.iteration == 0 ? psnr : 0.05 * psnr + 0.95 * state_.ema_psnr;
  state_.iteration = it;
  return out;
}

const TrainView& Trainer::next_view(StepStats& out) {
  if (state_.view_stack.empty()) {
    state_.view_stack.resize(views_.size());
    std::iota(state_.view_stack.begin(), state_.view_stack.end(), std::uint32_t(0));
    std::shuffle(state_.view_stack.begin(), state_.view_stack.end(), state_.rng);
  }
  out.view = int(state_.view_stack.back());
  state_.view_stack.pop_back();
  return views_[std::size_t(out.view)];
}

ImageGradients Trainer::LossGradients::upload(Device device) {
  ImageGradients go;
  on_device.clear();
  on_device.reserve(8);
  auto up = [&](const std::vector<float>& host, const float*& ptr) {
    if (host.empty()) return;
    ptr = on_device.emplace_back(host, device).data();
  };
  up(color, go.color);
  up(depth, go.depth);
  up(alpha, go.alpha);
  up(median, go.median_depth);
  up(normal, go.normal);
  up(extras, go.extras);
  up(detached, go.extras_detached);
  up(base, go.base_color);
  return go;
}

GaussianGradView Trainer::backward(const GaussianView& gv, LossGradients& g, bool with_extras) {
  GaussianModel& m = state_.model;
  m.zero_grad();
  if (view_grad_norm_.size() != m.count() || view_grad_norm_.device() != device_)
    view_grad_norm_ = Buffer<float>(m.count(), device_);
  view_grad_norm_.fill_zero();
  GaussianGradView gg = m.grad_view(with_extras);
  gg.mean2d_grad_norm = view_grad_norm_.data();
  renderer_->backward(gv, g.upload(device_), gg);
  return gg;
}

void Trainer::optimizer_step(int it) {
  GaussianModel& m = state_.model;
  const int decay_steps = config_.lr.position_max_steps > 0 ? config_.lr.position_max_steps : config_.iterations;
  for (ParamGroup g : active_groups()) {
    float lr = 0;
    switch (g) {
      case ParamGroup::Position:
        lr = exponential_lr(it, config_.lr.position_init * extent_, config_.lr.position_final * extent_, decay_steps);
        break;
      case ParamGroup::Scale: lr = config_.lr.scale; break;
      case ParamGroup::Rotation: lr = config_.lr.rotation; break;
      case ParamGroup::Opacity: lr = config_.lr.opacity; break;
      case ParamGroup::ShDc: lr = config_.sh_dc_rate(); break;
      case ParamGroup::ShRest: lr = config_.lr.sh_rest; break;
      case ParamGroup::Materials: lr = config_.lr.materials; break;
      case ParamGroup::Region: lr = config_.lr.region; break;
      case ParamGroup::Label: lr = config_.lr.label; break;
    }
    state_.adam.step(m, g, float(lr * state_.lr_scale), g == ParamGroup::ShRest ? 3 * (m.sh_degree + 1) * (m.sh_degree + 1) : 0);
  }
  if (const std::string bad = non_finite_parameter(); !bad.empty())  // an update cannot be undone: stop
    throw Error(format_iteration_problem(it, bad + " became non-finite; stopping, the checkpoints on disk are intact"));
  renderer_->step_own_parameters(it);
}

DensifyCounts Trainer::densify(int it) {
  // An opacity reset only happens when a pruning step follows it inside the window (otherwise the Gaussians
  // it silenced would never be removed, only dimmed).
  GaussianModel& m = state_.model;
  const DensifySettings& ds = config_.densify;
  const int until = densify_until();
  const int reset_every = config_.opacity_reset_every();
  DensifyCounts counts;
  if (it <= until) {
    if (it >= ds.from_iter && it % ds.interval == 0) {
      counts = densify_and_prune(m, state_.stats, ds, extent_, it > reset_every,
                                 config_.seed * 0x9e3779b97f4a7c15ull + std::uint64_t(it));
      if (m.count() == 0)
        throw Error(format_iteration_problem(
            it, "pruning removed every Gaussian (opacities below " + std::to_string(ds.min_opacity) +
                    "); stopping, the checkpoints on disk are intact"));
      model_changed();
    }
    if (it % reset_every == 0 && it + ds.interval <= until) reset_opacity(m, ds.reset_opacity);
  } else if (config_.anti_aliasing.filter_3d && it % config_.anti_aliasing.filter_3d_interval == 0 &&
             it < config_.iterations - config_.anti_aliasing.filter_3d_interval) {
    compute_filter3d(m, cameras());
  }
  return counts;
}

void Trainer::model_changed() {
  state_.stats.reset(state_.model.count(), device_);
  if (config_.anti_aliasing.filter_3d) compute_filter3d(state_.model, cameras());
}

std::string Trainer::non_finite_gradient() const {
  const GaussianModel& m = state_.model;
  for (ParamGroup g : active_groups()) {
    const GroupSpan span = group_span(g);
    const ParamTensor& t = m.tensor(span.param);
    const size_t bad = first_non_finite(t.grad.data(), t.grad.size(), device_);
    if (bad == t.grad.size()) continue;
    const size_t col = bad % size_t(t.width);
    if (int(col) < span.col_begin || int(col) >= span.col_end) continue;  // another group of the tensor
    return std::string("parameter group '") + group_name(g) + "' (Gaussian " + std::to_string(bad / t.width) + ")";
  }
  return {};
}

std::string Trainer::non_finite_parameter() const {
  const GaussianModel& m = state_.model;
  for (ParamGroup g : active_groups()) {
    const GroupSpan span = group_span(g);
    const ParamTensor& t = m.tensor(span.param);
    const size_t bad = first_non_finite(t.value.data(), t.value.size(), device_);
    if (bad == t.value.size()) continue;
    const size_t col = bad % size_t(t.width);
    if (int(col) < span.col_begin || int(col) >= span.col_end) continue;
    return std::string("parameter group '") + group_name(g) + "' (Gaussian " + std::to_string(bad / t.width) + ")";
  }
  return {};
}

void Trainer::skip_step(int it, const std::string& problem, StepStats& out) {
  if (config_.nan.policy == NanPolicy::Stop)
    throw Error(format_iteration_problem(it, problem + "; stopping (nan_policy stop), the checkpoints on disk are intact"));
  ++consecutive_skips_;
  if (consecutive_skips_ > config_.nan.max_skips)
    throw Error(format_iteration_problem(
        it, problem + "; " + std::to_string(consecutive_skips_) +
                " steps in a row were not finite even with the learning rates lowered to " +
                std::to_string(state_.lr_scale) + "x; stopping, the checkpoints on disk are intact"));
  state_.model.zero_grad();
  state_.lr_scale *= config_.nan.lr_factor;
  ++state_.skipped_steps;
  out.skipped = true;
  out.problem = format_iteration_problem(it, problem) + "; step skipped, learning rates now " +
                std::to_string(state_.lr_scale) + "x";
  state_.iteration = it;
}

std::vector<ParamGroup> Trainer::active_groups() const {
  std::vector<ParamGroup> g(std::begin(kRadianceGroups), std::end(kRadianceGroups));
  if (renderer_->wants_extras()) g.insert(g.end(), {ParamGroup::Materials, ParamGroup::Region, ParamGroup::Label});
  return g;
}

void Trainer::load_renderer_state(const std::filesystem::path& checkpoint, DifferentiableRenderer& renderer) {
  const std::filesystem::path p = renderer_state_path(checkpoint);
  if (!std::filesystem::exists(p)) {
    if (!renderer.save_own_state().empty())
      throw Error(p.string(), "missing: the checkpoint's environment map and roughness net are not beside it");
    return;
  }
  const std::vector<uint8_t> bytes = read_file_bytes(p);
  renderer.load_own_state(std::string(bytes.begin(), bytes.end()), p.string());
}

int Trainer::densify_until() const { return config_.densify_until(); }

TrainProgress Trainer::progress(double it_per_s) const {
  TrainProgress p;
  p.iteration = state_.iteration;
  p.total = config_.iterations;
  p.loss = state_.ema_loss;
  p.psnr = state_.ema_psnr;
  p.gaussians = state_.model.count();
  p.it_per_s = it_per_s;
  p.eta_s = it_per_s > 0 ? double(config_.iterations - state_.iteration) / it_per_s : 0;
  p.elapsed_s = state_.elapsed_s;
  return p;
}

void Trainer::save_checkpoint(const std::filesystem::path& path) {
  store_hook_states();
  // The renderer's part first: a checkpoint file never exists without its companion.
  const std::string own = renderer_->save_own_state();
  if (!own.empty()) write_file_bytes(renderer_state_path(path), own.data(), own.size());
  write_checkpoint(path, config_, state_);
}

namespace {

// log.csv: one line per log interval; on resume, lines past the checkpoint's iteration are dropped so the
// log never repeats iterations.
class CsvLog {
 public:
  static constexpr const char* kHeader = "iteration,loss,psnr,gaussians,elapsed_s,it_per_s";

  CsvLog(const std::filesystem::path& path, int resume_iteration) : path_(path) {
    std::vector<std::string> keep;
    if (std::filesystem::exists(path)) {
      std::ifstream in(path);
      std::string line;
      while (std::getline(in, line)) {
        if (line.empty() || line == kHeader) continue;
        if (std::atoi(line.c_str()) <= resume_iteration) keep.push_back(line);
      }
    }
    std::string text = std::string(kHeader) + "\n";
    for (const auto& l : keep) text += l + "\n";
    write_file_bytes(path, text.data(), text.size());
    out_.open(path, std::ios::app);
    if (!out_) throw Error(path.string(), "cannot append to the training log");
  }
  void add(int it, double loss, double psnr, size_t gaussians, double elapsed, double it_per_s) {
    char line[256];
    std::snprintf(line, sizeof line, "%d,%.6f,%.4f,%zu,%.3f,%.3f\n", it, loss, psnr, gaussians, elapsed, it_per_s);
    out_ << line;
    out_.flush();
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
};

}  // namespace

Trainer::RunResult Trainer::run(const RunOptions& o) {
  using clock = std::chrono::steady_clock;
  std::optional<CsvLog> log;
  if (!o.run_dir.empty()) {
    std::filesystem::create_directories(o.run_dir / "checkpoints");
    remove_stale_temp_files(o.run_dir / "checkpoints");  // left by a process killed while writing one
    remove_stale_temp_files(o.run_dir);
    log.emplace(o.run_dir / "log.csv", state_.iteration);
  }
  auto checkpoint = [&] {
    if (o.run_dir.empty()) return;
    save_checkpoint(checkpoint_path(o.run_dir, state_.iteration));
    remove_old_checkpoints(o.run_dir, config_.bookkeeping.keep_checkpoints);
  };
  // What the density control did, for the user.
  auto tell = [&](const std::string& note) {
    if (o.on_note)
      o.on_note(note);
    else
      std::printf("\n%s\n", note.c_str());
  };
  // Interval means for the log; a smoothed iteration time (about the last 50 iterations) for the rate.
  double sum_loss = 0, sum_psnr = 0;
  int n_sum = 0;
  double ema_dt = 0, it_per_s = 0;
  auto last = clock::now();

  for (;;) {
    // before_step also runs once the iterations are done: a decision due at the last iteration (--mode auto
    // on a short run, train/setup/auto_mode.h) may lengthen the run.
    if (o.before_step) {
      const auto t0 = clock::now();
      o.before_step(*this);
      const auto t1 = clock::now();
      state_.elapsed_s += std::chrono::duration<double>(t1 - t0).count();
      last += t1 - t0;
    }
    if (finished()) break;
    if (o.stop && o.stop->load()) {
      checkpoint();
      if (o.on_progress) o.on_progress(progress(it_per_s));
      return RunResult::Stopped;
    }
    const StepStats s = step();
    if (s.skipped) {
      if (o.on_skip)
        o.on_skip(s.problem);
      else
        std::fprintf(stderr, "\nwarning: %s\n", s.problem.c_str());
      last = clock::now();
      continue;
    }
    if (!s.densify_note.empty()) tell(s.densify_note);
    const auto now = clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    state_.elapsed_s += dt;
    ema_dt = ema_dt == 0 ? dt : 0.98 * ema_dt + 0.02 * dt;
    it_per_s = ema_dt > 0 ? 1.0 / ema_dt : 0;
    sum_loss += s.loss;
    sum_psnr += std::min(s.psnr, 99.0);
    ++n_sum;
    const int it = state_.iteration;
    if (log && (it % config_.bookkeeping.log_interval == 0 || finished())) {
      log->add(it, sum_loss / n_sum, sum_psnr / n_sum, state_.model.count(), state_.elapsed_s, it_per_s);
      sum_loss = sum_psnr = 0;
      n_sum = 0;
    }
    const int checkpoint_every = config_.bookkeeping.checkpoint_interval;
    if (checkpoint_every > 0 && it % checkpoint_every == 0 && !finished()) checkpoint();
    if (o.on_progress && (it % std::max(o.progress_every, 1) == 0 || finished())) o.on_progress(progress(it_per_s));
  }
  checkpoint();
  return RunResult::Finished;
}

}  // namespace goris
