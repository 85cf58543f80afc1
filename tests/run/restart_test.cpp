// Checkpoint and restart (run/checkpoint.hpp; issue 18, item 2): a run
// continued from its checkpoint writes the same CSV rows (all but the wall
// times) and the same VTU files, bit for bit, as the uninterrupted run — with
// fracture, and with damage handing over to a growing α (rebuilt
// discretization); a stop between increments leaves a checkpoint; a changed
// case, a truncated or foreign file and missing output are refused with a
// message that names what is wrong.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/core/interrupt.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/checkpoint.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/fracture_cases.hpp"

#include "perimorph/la/petsc_session.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace perimorph {
namespace {

namespace fs = std::filesystem;

/// A fresh folder of this process (CTest runs each test in its own process,
/// several at once: the suite's shared runs must not meet).
std::string scratch_dir(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("perimorph_restart_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A CSV's text without its timing columns (wall_time, remodel_time): what
/// must be bit-identical between two runs of one case.
std::string csv_without_times(const fs::path& path) {
  std::istringstream in(read_text(path));
  std::string line, out;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (keep.empty())
      for (const auto& c : cells) keep.push_back(c != "wall_time" && c != "remodel_time");
    for (std::size_t k = 0; k < cells.size() && k < keep.size(); ++k)
      if (keep[k]) out += cells[k] + ',';
    out += '\n';
  }
  return out;
}

/// Every file of `expected` (the checkpoint and the lock aside) is in `actual` with the
/// same content (CSVs without their timing columns).
void expect_same_output(const std::string& expected, const std::string& actual) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(expected)) {
    const fs::path name = entry.path().filename();
    if (name.extension() == ".checkpoint" || name.extension() == ".lock") continue;
    ++files;
    const fs::path other = fs::path(actual) / name;
    ASSERT_TRUE(fs::exists(other)) << other;
    if (name.extension() == ".csv")
      EXPECT_EQ(csv_without_times(entry.path()), csv_without_times(other)) << name;
    else
      EXPECT_TRUE(read_text(entry.path()) == read_text(other)) << name << " differs";
  }
  EXPECT_GT(files, 3);
}

casefile::CaseConfig fracture_plate() {
  return casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) +
                                   "/examples/fracture_plate_2d/case.toml");
}

/// Runs the first `increments` increments of `disc` into `dir` as run_static
/// does, with a checkpoint after the last of them, and stops there.
void run_until(const setup::Discretization& disc, const std::string& dir, int increments) {
  run::RunOptions options{dir, true};
  options.checkpoint_every = increments;
  run::QuasiStaticRun run(disc, options);
  for (int i = 0; i < increments; ++i) {
    run.apply_load(i);
    run.solve();
    while (run.evolve()) run.solve();
    run.write_increment();
    run.adapt_for_next();
    run.checkpoint_if_due();
  }
}

/// The example's uninterrupted run, and one stopped after a checkpoint at
/// increment 8 (bonds fail in increments 2 to 11): made once for the tests
/// below.
class RestartFracture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    config_ = new casefile::CaseConfig(fracture_plate());
    disc_ = new setup::Discretization(setup::build_discretization(*config_));
    full_ = scratch_dir("full");
    run::run_static(*disc_, {full_, true});
    checkpointed_ = scratch_dir("checkpointed");
    run_until(*disc_, checkpointed_, 8);
  }
  static void TearDownTestSuite() {
    fs::remove_all(full_);
    fs::remove_all(checkpointed_);
    delete disc_;
    delete config_;
  }
  static std::string checkpoint() { return checkpointed_ + "/fracture_plate.checkpoint"; }
  /// A copy of the checkpointed run's output (each test continues its own).
  static std::string copy_of_checkpointed(const std::string& name) {
    const std::string dir = scratch_dir(name);
    fs::copy(checkpointed_, dir);
    return dir;
  }

  static casefile::CaseConfig* config_;
  static setup::Discretization* disc_;
  static std::string full_, checkpointed_;
};
casefile::CaseConfig* RestartFracture::config_ = nullptr;
setup::Discretization* RestartFracture::disc_ = nullptr;
std::string RestartFracture::full_, RestartFracture::checkpointed_;

TEST_F(RestartFracture, ContinuedRunWritesTheUninterruptedRunBitForBit) {
  const std::string dir = copy_of_checkpointed("continued");
  run::RunOptions options{dir, true};
  options.restart = dir;
  const auto summary = run::run_static(*disc_, options);
  EXPECT_EQ(summary.restarted_after, 8);
  EXPECT_EQ(summary.increments_done, 30);
  ASSERT_EQ(summary.history.size(), 22u);
  expect_same_output(full_, dir);
  const auto rows = testing::read_rows(dir + "/fracture_plate.csv");
  ASSERT_EQ(rows.size(), 30u);
  EXPECT_GT(rows.back().at("bonds_broken"), rows[7].at("bonds_broken")) << "no bond failed after the restart";
}

TEST_F(RestartFracture, AStopBetweenIncrementsLeavesACheckpointToContinue) {
  const std::string dir = scratch_dir("stopped");
  {
    run::QuasiStaticRun run(*disc_, {dir, true});
    try {
      for (int i = 0; i < run.increments(); ++i) {
        if (i == 10) set_stop_request(SIGTERM);
        run.apply_load(i);
        run.solve();
        while (run.evolve()) run.solve();
        run.write_increment();
        run.adapt_for_next();
        run.checkpoint_if_due();
      }
      ADD_FAILURE() << "the run did not stop";
    } catch (const Interrupted& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("The checkpoint of increment 10 is"), std::string::npos) << what;
      EXPECT_NE(what.find("--restart"), std::string::npos) << what;
    }
    set_stop_request(0);
  }
  ASSERT_TRUE(fs::exists(dir + "/fracture_plate.checkpoint"));
  run::RunOptions options{dir, true};
  options.restart = dir + "/fracture_plate.checkpoint";
  EXPECT_EQ(run::run_static(*disc_, options).restarted_after, 10);
  expect_same_output(full_, dir);
}

TEST_F(RestartFracture, RefusesAChangedCaseNamingTheKeys) {
  std::string text = read_text(config_->path);
  const std::string from = "\ns_crit = 0.005", to = "\ns_crit = 0.006";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), to);
  const auto changed = casefile::parse_case_string(text, config_->path);
  const auto disc = setup::build_discretization(changed);
  const std::string dir = copy_of_checkpointed("changed");
  run::RunOptions options{dir, true};
  options.restart = dir;
  try {
    run::run_static(disc, options);
    FAIL() << "a changed case was continued";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fracture.s_crit: 0.005 in the checkpoint, 0.006 now"), std::string::npos) << what;
  }
}

TEST_F(RestartFracture, RefusesATruncatedForeignOrNewerCheckpoint) {
  const std::string dir = copy_of_checkpointed("broken");
  const std::string path = dir + "/fracture_plate.checkpoint";
  const std::string bytes = read_text(path);
  auto expect_refused = [&](const std::string& content, const std::string& message) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << content;
    run::RunOptions options{dir, true};
    options.restart = path;
    try {
      run::run_static(*disc_, options);
      ADD_FAILURE() << "continued from a bad checkpoint: " << message;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  expect_refused(bytes.substr(0, bytes.size() / 2), "corrupt or truncated checkpoint");
  expect_refused(bytes.substr(0, bytes.size() - 1), "corrupt or truncated checkpoint");
  expect_refused("", "not a perimorph checkpoint");  // an empty file (nothing to map)
  expect_refused("increment,load_factor\n1,0.5\n", "not a perimorph checkpoint");
  std::string newer = bytes;
  const std::size_t version_at = sizeof(std::uint64_t) + std::string("perimorph-checkpoint").size();
  const std::uint32_t version = run::kCheckpointVersion + 1;
  newer.replace(version_at, sizeof version, reinterpret_cast<const char*>(&version), sizeof version);
  expect_refused(newer, "checkpoint format version " + std::to_string(version) +
                            ", this perimorph reads version " + std::to_string(run::kCheckpointVersion));
}

TEST_F(RestartFracture, NeedsTheOutputItContinues) {
  const std::string dir = scratch_dir("elsewhere");
  run::RunOptions options{dir, true};
  options.restart = checkpoint();
  try {
    run::run_static(*disc_, options);
    FAIL() << "continued into a folder without the run's files";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot continue"), std::string::npos) << e.what();
  }
  options.restart = scratch_dir("nothing_there");
  EXPECT_THROW(run::run_static(*disc_, options), InputError);
}

/// Runs `disc` with a checkpoint every `every` increments (its output kept as
/// the uninterrupted run's), continues it in place from its last checkpoint
/// (after increment `after`), and expects the same files. Returns the folder
/// of the uninterrupted output.
std::string expect_continued_run_bit_for_bit(const setup::Discretization& disc, const std::string& name,
                                             int every, int after) {
  const std::string dir = scratch_dir(name), full = scratch_dir(name + "_full");
  run::RunOptions options{dir, true};
  options.checkpoint_every = every;
  run::run_static(disc, options);
  fs::copy(dir, full);
  options.restart = dir;
  EXPECT_EQ(run::run_static(disc, options).restarted_after, after);
  expect_same_output(full, dir);
  return full;
}

TEST(Restart, DamageHandoverWithAGrowingAlphaContinuesBitForBit) {
  // λ to 0.75 in five increments, then 0.85, 0.95, 1.0 (473 bonds failed at
  // the end): its own last three, 0.9, 1.05 and 1.2, made this the longest
  // unit test (55 s alone, now 33 s).
  auto c = testing::handover_plate(8);
  c.loading.factors = {0.15, 0.3, 0.45, 0.6, 0.75, 0.85, 0.95, 1.0};
  const setup::Discretization disc = setup::build_discretization(c);
  // One run with a checkpoint at increment 5 gives the uninterrupted output
  // (kept) and the checkpoint; the continued run rewrites increments 6 to 8
  // in place (the case writes CSVs only: their rows after the checkpoint are
  // cut off first).
  const std::string full = expect_continued_run_bit_for_bit(disc, "handover", 5, 5);
  // The checkpoint is taken on a grown α (a rebuilt discretization); α grows
  // again and bonds fail after it.
  const auto rows = testing::read_rows(full + "/test.csv");
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_GT(rows[4].at("alpha_balls"), 0.0);
  EXPECT_GT(rows[7].at("alpha_balls"), rows[4].at("alpha_balls"));
  EXPECT_GT(rows[7].at("bonds_broken"), rows[4].at("bonds_broken"));
}

TEST(Restart, MatrixFreeRunContinuesBitForBit) {
  // [solver] operator = "matrix-free" (system/matrix_free_stiffness.hpp): the
  // checkpoint holds no matrix; the continued run rebuilds the operator.
  auto c = testing::box_case(3, {7, 6, 5}, Vec3(7.0, 6.0, 5.0), 200.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::pmb, 2.2, 0.0, 1,
                        casefile::Discretization::discontinuous_constant);
  c.alpha.value = 1.0;
  c.solver.op = casefile::SolverOperator::matrix_free;
  la::set_option("-ksp_type", "cg");  // not a direct solve left by another test in this process
  la::set_option("-pc_type", "gamg");
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmin", 2),
                 testing::fixed("xmax", 0, 0.05)};
  c.loading.factors = {0.25, 0.5, 0.75, 1.0};
  c.output.vtu = true;
  const setup::Discretization disc = setup::build_discretization(c);
  expect_continued_run_bit_for_bit(disc, "matrix_free", 3, 3);
}

}  // namespace
}  // namespace perimorph
