#include "ui/display/background_priority.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <tbb/task_scheduler_observer.h>
#include <unistd.h>

#include <cerrno>

namespace goris::ui {

// Watches the implicit TBB arena of the thread that creates it: every worker joining it is lowered.
class BackgroundPriority::Observer final : public tbb::task_scheduler_observer {
 public:
  Observer() { observe(true); }
  ~Observer() override { observe(false); }
  void on_scheduler_entry(bool is_worker) override {
    if (is_worker) lower_current_thread();
  }
};

void BackgroundPriority::lower_current_thread() {
  // On Linux `nice` is per thread: PRIO_PROCESS with a thread id changes that thread alone. Only ever
  // raise the value (lower the priority); failing is harmless (the thread just keeps its priority).
  const pid_t tid = pid_t(syscall(SYS_gettid));
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, id_t(tid));
  if (errno == 0 && now < kNice) setpriority(PRIO_PROCESS, id_t(tid), kNice);
}

BackgroundPriority::BackgroundPriority() {
  lower_current_thread();
  observer_ = std::make_unique<Observer>();
}

BackgroundPriority::~BackgroundPriority() = default;

}  // namespace goris::ui
