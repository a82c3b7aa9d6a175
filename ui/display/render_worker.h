#pragma once
// Renders the viewports' view on a worker thread so that the GUI keeps its frame rate: the GUI posts the
// latest (model snapshot, camera) and picks up finished frames; a request that is overtaken before it
// starts is dropped. Rendering uses the engine on the snapshot's device (ui/display/display_renderer.h: the
// rasterizer, the intrinsic renderer for intrinsic runs, the selection's coverage); frames of a CUDA
// snapshot keep their images on the GPU for FrameTextures' interop copy.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/scene/selection_points.h"
#include "ui/display/display_frame.h"
#include "ui/display/model_snapshot.h"

namespace goris::ui {

struct RenderRequest {
  std::shared_ptr<const ModelSnapshot> model;  // rendered with its own settings
  Camera camera;
  std::shared_ptr<const SelectionMask> selection;  // null = nothing selected
  std::shared_ptr<const SelectionMask> hidden;     // not drawn; null = none
};

class RenderWorker {
 public:
  RenderWorker();
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  // Queues a request, replacing one that has not started; returns its id (frames carry it).
  std::uint64_t request(RenderRequest r);
  // The newest finished frame not yet taken, or null.
  std::shared_ptr<const DisplayFrame> take();
  // True when nothing is queued or rendering: the last taken frame answers the last request.
  bool idle() const;
  // The last rendering failure (empty when the last request succeeded).
  std::string error() const;

 private:
  void loop();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RenderRequest> pending_;
  std::uint64_t pending_id_ = 0, next_id_ = 1;
  bool busy_ = false, quit_ = false;
  std::shared_ptr<const DisplayFrame> done_;
  std::string error_;
  std::thread thread_;
};

}  // namespace goris::ui
