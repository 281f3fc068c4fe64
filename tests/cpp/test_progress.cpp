// Progress and cancellation of a set-up (progress.h): the fraction runs from 0 to 1 through the
// phases' slices and never goes back, phases are named, a cancel is seen by every check, and workers
// may report from several threads at once.
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "gauss/util/progress.h"

// Each test file in a namespace of its own: a unity build (CMAKE_UNITY_BUILD) compiles several in one
// translation unit, where the helpers of different files would clash.
namespace test_progress {

namespace {

using gauss::SetupPhase;

constexpr int kPhases = static_cast<int>(SetupPhase::count);

SetupPhase phase(int p) { return static_cast<SetupPhase>(p); }

}  // namespace

TEST(Progress, PhaseNames) {
  const char* expected[kPhases] = {"topology", "weights", "ordering", "symbolic", "factorizing"};
  for (int p = 0; p < kPhases; ++p) EXPECT_STREQ(gauss::phase_name(phase(p)), expected[p]);
}

TEST(Progress, FractionRisesFromZeroToOneThroughThePhases) {
  // A whole set-up and a re-factorization (the last phases only) both span the full 0..1.
  for (SetupPhase first : {SetupPhase::topology, SetupPhase::symbolic}) {
    SCOPED_TRACE(gauss::phase_name(first));
    gauss::Progress progress;
    EXPECT_STREQ(progress.phase(), "");
    EXPECT_FALSE(progress.running());
    progress.start(first);
    EXPECT_TRUE(progress.running());
    EXPECT_EQ(progress.fraction(), 0.0);
    double last = 0.0;
    for (int p = static_cast<int>(first); p < kPhases; ++p) {
      progress.enter(phase(p));
      EXPECT_STREQ(progress.phase(), gauss::phase_name(phase(p)));
      const double slice_start = progress.fraction();
      EXPECT_GE(slice_start, last);
      EXPECT_LT(slice_start, 1.0);
      progress.advance(0.5);
      const double half = progress.fraction();
      EXPECT_GT(half, slice_start);
      progress.advance(0.25);  // a smaller report never lowers the fraction
      EXPECT_EQ(progress.fraction(), half);
      progress.advance(7.0);  // clamped to the end of the slice
      last = progress.fraction();
      EXPECT_LE(last, 1.0);
    }
    EXPECT_DOUBLE_EQ(last, 1.0);  // the last slice ends at 1
    progress.finish();
    EXPECT_EQ(progress.fraction(), 1.0);
    EXPECT_STREQ(progress.phase(), "done");
    EXPECT_FALSE(progress.running());
    // Phases the set-up did not run took no time.
    for (int p = 0; p < static_cast<int>(first); ++p) EXPECT_EQ(progress.seconds(phase(p)), 0.0);
    for (int p = static_cast<int>(first); p < kPhases; ++p) EXPECT_GE(progress.seconds(phase(p)), 0.0);
  }
}

TEST(Progress, EachPhaseStartsWhereThePreviousEnds) {
  gauss::Progress progress;
  progress.start(SetupPhase::topology);
  for (int p = 0; p < kPhases; ++p) {
    progress.enter(phase(p));
    const double start = progress.fraction();
    progress.advance(1.0);
    const double end = progress.fraction();
    EXPECT_GT(end, start) << gauss::phase_name(phase(p));  // every phase owns a slice
    if (p + 1 < kPhases) {
      progress.enter(phase(p + 1));
      EXPECT_DOUBLE_EQ(progress.fraction(), end) << gauss::phase_name(phase(p + 1));
    }
  }
}

TEST(Progress, CancelIsSeenByEveryCheckAndStays) {
  gauss::Progress progress;
  progress.start(SetupPhase::topology);
  progress.enter(SetupPhase::weights);
  EXPECT_NO_THROW(progress.check());
  std::thread([&] { progress.cancel(); }).join();  // from another thread, as the add-on's UI does
  EXPECT_TRUE(progress.cancelled());
  EXPECT_THROW(progress.check(), gauss::Cancelled);
  EXPECT_THROW(progress.enter(SetupPhase::ordering), gauss::Cancelled);
  EXPECT_THROW(progress.start(SetupPhase::topology), gauss::Cancelled);  // a cancelled Progress stays so
  EXPECT_TRUE(progress.cancelled());
  try {
    progress.check();
  } catch (const std::runtime_error& e) {  // Cancelled is a runtime_error with a message
    EXPECT_NE(std::string(e.what()).find("cancelled"), std::string::npos);
  }
}

TEST(Progress, WorkersReportFromManyThreadsAndTheFractionOnlyGrows) {
  gauss::Progress progress;
  progress.start(SetupPhase::ordering);
  progress.enter(SetupPhase::ordering);
  const double start = progress.fraction();
  std::vector<std::thread> workers;
  for (int t = 0; t < 4; ++t)
    workers.emplace_back([&progress, t] {
      for (int k = 0; k <= 1000; ++k) progress.advance((k * 4 + t) / 4003.0);
    });
  double last = start;
  bool monotone = true;
  for (int k = 0; k < 2000; ++k) {
    const double f = progress.fraction();
    monotone = monotone && f >= last;
    last = f;
  }
  for (auto& w : workers) w.join();
  EXPECT_TRUE(monotone);
  // The largest report (4003 / 4003) wins whatever order the threads ran in.
  const double reached = progress.fraction();
  progress.enter(SetupPhase::symbolic);
  EXPECT_DOUBLE_EQ(reached, progress.fraction());
}

}  // namespace test_progress
