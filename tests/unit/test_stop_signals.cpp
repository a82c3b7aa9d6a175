// The CLI's stop handler: SIGINT, SIGTERM and SIGHUP each stop the work gracefully and give the command the
// shell's exit status for that signal; one interrupt delivered twice in quick succession (timeout(1)
// signals the child and then its process group) must not kill the process.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "app/cli_common/stop_signals.h"

namespace goris::cli {
namespace {

TEST(StopSignals, FirstInterruptRaisesTheStopFlag) {
  const StopSignals stop;
  EXPECT_FALSE(*stop.flag());
  EXPECT_EQ(stop.exit_code(), 0);
  std::raise(SIGINT);
  EXPECT_TRUE(*stop.flag());
  EXPECT_EQ(stop.exit_code(), 130);
}

TEST(StopSignals, TerminateAndHangUpStopToo) {
  {
    const StopSignals stop;
    std::raise(SIGTERM);
    EXPECT_TRUE(*stop.flag());
    EXPECT_EQ(stop.signal(), SIGTERM);
    EXPECT_EQ(stop.exit_code(), 143);
  }
  {
    const StopSignals stop;
    EXPECT_FALSE(*stop.flag());  // a new object starts unstopped
    std::raise(SIGHUP);
    EXPECT_TRUE(*stop.flag());
    EXPECT_EQ(stop.exit_code(), 129);
    EXPECT_EQ(stop_signal_name(stop.signal()), "SIGHUP");
  }
}

TEST(StopSignals, RepeatWithinHalfASecondIsTheSameInterrupt) {
  const StopSignals stop;
  std::raise(SIGINT);
  std::raise(SIGINT);  // would end the process if taken as a second Ctrl-C
  std::raise(SIGINT);
  EXPECT_TRUE(*stop.flag());
}

TEST(StopSignals, SecondInterruptLaterEndsTheProcess) {
  EXPECT_EXIT(
      {
        const StopSignals stop;
        std::raise(SIGINT);
        std::this_thread::sleep_for(std::chrono::milliseconds(600));
        std::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::KilledBySignal(SIGINT), "");
}

TEST(StopSignals, ADifferentSecondSignalEndsTheProcess) {
  EXPECT_EXIT(
      {
        const StopSignals stop;
        std::raise(SIGTERM);
        std::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::KilledBySignal(SIGINT), "");
}

TEST(StopSignals, PreviousHandlersComeBack) {
  const auto int_before = std::signal(SIGINT, SIG_IGN);
  const auto term_before = std::signal(SIGTERM, SIG_IGN);
  { const StopSignals stop; }
  EXPECT_EQ(std::signal(SIGINT, int_before), SIG_IGN);
  EXPECT_EQ(std::signal(SIGTERM, term_before), SIG_IGN);
}

}  // namespace
}  // namespace goris::cli
