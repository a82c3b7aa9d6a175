#pragma once
// What one evaluation of the guided two-click flow (ui/document/two_click_flow.h) works with: its clicks,
// its progress and what it found. The selection worker fills them in (SelectionSession::click_regions,
// ui/selection/two_click_session.cpp); the flow, its panel and scripts read them.
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/scene/selection_points.h"

namespace goris::ui {

// A click of the flow: pixel (x, y) of training view `view` at the run's training resolution.
struct FlowClick {
  std::size_t view = 0;
  int x = 0, y = 0;
};

// How far the running evaluation is; shared with the selection worker.
struct FlowProgress {
  std::atomic<int> done{0}, total{0};
  std::atomic<bool> cancel{false};
  void set_stage(const std::string& s) {
    std::lock_guard lk(mutex);
    stage = s;
  }
  std::string get_stage() const {
    std::lock_guard lk(mutex);
    return stage;
  }

 private:
  mutable std::mutex mutex;
  std::string stage;
};

// What one evaluation found (written by the worker before its job finishes, read-only afterwards).
struct FlowResult {
  std::vector<FlowClick> clicks;
  std::vector<Mask> masks;          // every training view's object mask, at the training resolution
  std::vector<Mask> click_regions;  // each click's region of its view
  std::filesystem::path dir;        // where the masks were written
  std::size_t selected = 0, total = 0;
  std::shared_ptr<const SelectionMask> selection;  // what the evaluation selected
  // One click: the view offered for the second one and the point on the object there (its mask's
  // deepest pixel); none when no other view shows the object.
  std::optional<FlowClick> offered;
};

}  // namespace goris::ui
