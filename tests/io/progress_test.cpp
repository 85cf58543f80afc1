// The progress line (io/progress.hpp): the increment line counts elapsed time
// from the program's start (set-up included) and the ETA from the increments
// alone; the set-up line names the phase running and the times of those done;
// phases are recorded (for the summary) also when nothing is drawn.

#include "perimorph/io/progress.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace perimorph::io {
namespace {

TEST(IoProgress, FormatsLineAndStaysSilentWhenDisabled) {
  EXPECT_EQ(ProgressLine::format(3, 10, "load 0.3", 6.0, 6.0),
            "[increment 3/10] load 0.3 | elapsed 6.0 s | ETA 14.0 s");
  EXPECT_EQ(ProgressLine::format(0, 10, "", 0.04, 0.0), "[increment 0/10] | elapsed 0.0 s | ETA -");
  ProgressLine line(10, false);
  EXPECT_FALSE(line.active());
  line.update(1, "x");
  line.finish();
}

TEST(IoProgress, ElapsedCountsTheSetUpAndTheEtaOnlyTheIncrements) {
  // 12 s of set-up, then 3 increments in 6 s: elapsed 18 s, 2 s per increment.
  EXPECT_EQ(ProgressLine::format(3, 10, "", 18.0, 6.0), "[increment 3/10] | elapsed 18.0 s | ETA 14.0 s");
}

TEST(IoProgress, SetUpLineNamesThePhases) {
  const std::vector<ProgressLine::Phase> done{{"mesh", 0.01}, {"bond graph", 1.25}, {"morphed C", 4.0}};
  EXPECT_EQ(ProgressLine::format_setup(done, "assembly", 5.3),
            "[set-up] assembly... | bond graph 1.2 s, morphed C 4.0 s | elapsed 5.3 s");
  EXPECT_EQ(ProgressLine::format_setup({}, "mesh", 0.0), "[set-up] mesh... | elapsed 0.0 s");
  EXPECT_EQ(ProgressLine::format_setup(done, "", 5.3), "[set-up 5.3 s] bond graph 1.2 s, morphed C 4.0 s");
}

TEST(IoProgress, PhasesAreRecordedWhenNotDrawn) {
  const auto start = ProgressLine::clock::now() - std::chrono::seconds(2);
  ProgressLine line(4, false, start);
  line.phase("mesh");
  line.phase("assembly");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  line.start_increments();
  line.message("a warning is printed even when the line is off");
  ASSERT_EQ(line.phases().size(), 2u);
  EXPECT_EQ(line.phases()[0].name, "mesh");
  EXPECT_EQ(line.phases()[1].name, "assembly");
  EXPECT_GE(line.phases()[1].seconds, 0.015);
  EXPECT_LT(line.phases()[1].seconds, 1.9);  // from its own start, not the program's
}

}  // namespace
}  // namespace perimorph::io
