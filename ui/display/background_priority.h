#pragma once
// Engine work in the editor (training, viewport renders) runs at a lower CPU priority than the GUI thread,
// so the window stays responsive on a machine whose cores the trainer keeps busy. Construct one of these
// at the top of a worker thread: it lowers that thread's priority (Linux nice +10), and that of every TBB
// worker thread that joins the thread's parallel loops. Priorities are never raised again (an unprivileged
// process cannot), which is harmless: the editor's TBB workers only ever run engine work.
#include <memory>

namespace goris::ui {

class BackgroundPriority {
 public:
  BackgroundPriority();
  ~BackgroundPriority();
  BackgroundPriority(const BackgroundPriority&) = delete;
  BackgroundPriority& operator=(const BackgroundPriority&) = delete;

  // The nice value this class gives a thread.
  static constexpr int kNice = 10;
  // Lowers the calling thread only.
  static void lower_current_thread();

 private:
  class Observer;
  std::unique_ptr<Observer> observer_;
};

}  // namespace goris::ui
