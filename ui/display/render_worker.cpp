#include "ui/display/render_worker.h"

#include <chrono>

#include "ui/display/background_priority.h"
#include "ui/display/display_renderer.h"

namespace goris::ui {

RenderWorker::RenderWorker() : thread_([this] { loop(); }) {}

RenderWorker::~RenderWorker() {
  {
    std::lock_guard lk(mutex_);
    quit_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t RenderWorker::request(RenderRequest r) {
  std::lock_guard lk(mutex_);
  pending_ = std::move(r);
  pending_id_ = next_id_++;
  wake_.notify_all();
  return pending_id_;
}

std::shared_ptr<const DisplayFrame> RenderWorker::take() {
  std::lock_guard lk(mutex_);
  return std::exchange(done_, nullptr);
}

bool RenderWorker::idle() const {
  std::lock_guard lk(mutex_);
  return !pending_ && !busy_ && !done_;
}

std::string RenderWorker::error() const {
  std::lock_guard lk(mutex_);
  return error_;
}

void RenderWorker::loop() {
  const BackgroundPriority background;  // the GUI thread goes first
  DisplayRenderer renderer;             // lives on this thread: keeps the intrinsic renderer between frames
  for (;;) {
    RenderRequest r;
    std::uint64_t id = 0;
    {
      std::unique_lock lk(mutex_);
      wake_.wait(lk, [&] { return quit_ || pending_.has_value(); });
      if (quit_) return;
      r = std::move(*pending_);
      pending_.reset();
      id = pending_id_;
      busy_ = true;
    }
    std::shared_ptr<DisplayFrame> frame;
    std::string error;
    try {
      const auto t0 = std::chrono::steady_clock::now();
      frame = std::make_shared<DisplayFrame>(renderer.render(*r.model, r.camera, r.selection, r.hidden));
      frame->id = id;
      frame->model_iteration = r.model->iteration();
      frame->gaussians = r.model->count();
      frame->render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard lk(mutex_);
    busy_ = false;
    error_ = error;
    if (frame) done_ = std::move(frame);
  }
}

}  // namespace goris::ui
