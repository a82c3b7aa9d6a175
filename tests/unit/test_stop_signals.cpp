// The CLI's Ctrl-C handler: one interrupt delivered twice in quick succession (timeout(1) signals the child
// and then its process group) must stop the work gracefully, not kill the process.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "../../app/goris/ctrl_c.h"

namespace goris::cli {
namespace {

TEST(CtrlC, FirstInterruptRaisesTheStopFlag) {
  const CtrlC ctrl_c;
  EXPECT_FALSE(*ctrl_c.flag());
  std::raise(SIGINT);
  EXPECT_TRUE(*ctrl_c.flag());
}

TEST(CtrlC, RepeatWithinHalfASecondIsTheSameInterrupt) {
  const CtrlC ctrl_c;
  std::raise(SIGINT);
  std::raise(SIGINT);  // would end the process if taken as a second Ctrl-C
  std::raise(SIGINT);
  EXPECT_TRUE(*ctrl_c.flag());
}

TEST(CtrlC, SecondInterruptLaterEndsTheProcess) {
  EXPECT_EXIT(
      {
        const CtrlC ctrl_c;
        std::raise(SIGINT);
        std::this_thread::sleep_for(std::chrono::milliseconds(600));
        std::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::KilledBySignal(SIGINT), "");
}

TEST(CtrlC, PreviousHandlerComesBack) {
  const auto before = std::signal(SIGINT, SIG_IGN);
  { const CtrlC ctrl_c; }
  EXPECT_EQ(std::signal(SIGINT, before), SIG_IGN);
}

}  // namespace
}  // namespace goris::cli
