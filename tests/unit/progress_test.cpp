// Long work is never silent in a log: with stderr not a terminal (as under ctest), Progress
// writes a plain line now and then with the fraction, the time so far and an estimate.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "tellus/core/progress.hpp"

namespace tellus {
namespace {

TEST(Progress, WritesALineNowAndThenWhenStderrIsNotATerminal) {
  ::setenv("TELLUS_PROGRESS_LOG_SECONDS", "0.1", 1);
  testing::internal::CaptureStderr();
  {
    Progress progress("unit work", 10);
    for (int i = 0; i < 10; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(40));
      progress.advance();
    }
  }
  const std::string log = testing::internal::GetCapturedStderr();
  ::unsetenv("TELLUS_PROGRESS_LOG_SECONDS");
  EXPECT_NE(log.find("tellus: unit work: "), std::string::npos) << log;
  EXPECT_NE(log.find("% ("), std::string::npos) << log;
  EXPECT_NE(log.find("of 10), "), std::string::npos) << log;
  EXPECT_NE(log.find(" elapsed, "), std::string::npos) << log;
  EXPECT_NE(log.find(" left"), std::string::npos) << log;
  EXPECT_EQ(log.find('\r'), std::string::npos) << "no terminal redraws in a log";
  // About one line per 0.1 s of the 0.4 s: a few, not one per step.
  const auto lines = std::count(log.begin(), log.end(), '\n');
  EXPECT_GE(lines, 2);
  EXPECT_LE(lines, 8);
}

TEST(Progress, ShortWorkPrintsNothing) {
  testing::internal::CaptureStderr();
  {
    Progress progress("quick", 1000);
    for (int i = 0; i < 1000; ++i) progress.advance();
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Progress, QuietMeansQuiet) {
  ::setenv("TELLUS_PROGRESS_LOG_SECONDS", "0.1", 1);
  Progress::setEnabled(false);
  testing::internal::CaptureStderr();
  {
    Progress progress("hushed", 4);
    for (int i = 0; i < 4; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
      progress.advance();
    }
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  Progress::setEnabled(true);
  ::unsetenv("TELLUS_PROGRESS_LOG_SECONDS");
}

}  // namespace
}  // namespace tellus
