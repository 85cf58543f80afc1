// Checkpoints of runs with bond failure on pieces of the model (issue 17;
// run/whole_state.hpp): written in the whole model's numbers, as a run on
// parts writes them, so that each continues the other.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/floating_plate.hpp"
#include "support/fracture_cases.hpp"
#include "support/model_cases.hpp"
#include "support/same_answer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace perimorph {
namespace {

namespace fs = std::filesystem;

/// A run continued from the checkpoint in `from` (copied to `to` first),
/// writing its own checkpoint after the last increment, `last`.
run::RunSummary continued(const setup::Discretization& model, const fs::path& from, const fs::path& to,
                          int last) {
  if (la::world_rank() == 0) fs::copy(from, to, fs::copy_options::recursive);
  (void)la::any_over_processes(false);  // every process waits for the copy
  run::RunOptions options{to.string(), true};
  options.restart = to.string();
  options.checkpoint_every = last;
  return run::run_static(model, options);
}

/// The bytes of a checkpoint with its two wall times (the run's elapsed time
/// and its time spent rebuilding the model, 8 bytes each after the "run"
/// tag and after the count that follows it) zeroed.
std::string checkpoint_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string tag = std::string("\x03\0\0\0\0\0\0\0", 8) + "run";
  const std::size_t at = bytes.find(tag);
  if (at == std::string::npos || at + tag.size() + 24 > bytes.size()) return {};
  for (std::size_t k : {std::size_t{0}, std::size_t{16}}) bytes.replace(at + tag.size() + k, 8, 8, '\0');
  return bytes;
}

/// Each case run on the parts and on the pieces with a checkpoint after its
/// second increment, each checkpoint continued on the other and on its own
/// (comments of the tests below), in `root`.
void expect_continued_alike(const std::vector<testing::NamedCase>& cases, const fs::path& root) {
  const int processes = la::world_size();
  if (la::world_rank() == 0) fs::remove_all(root);
  (void)la::any_over_processes(false);
  const bool bitwise = processes <= 2;
  for (auto [name, config] : cases) {
    SCOPED_TRACE(name);
    config.output.checkpoint_every = 2;
    const setup::Discretization part = run::process_part(config);
    const setup::Discretization piece = run::process_model(config);
    ASSERT_TRUE(piece.piece != nullptr);
    const fs::path on_part = root / name / "part", on_piece = root / name / "piece";
    const run::RunSummary part_run = run::run_static(part, {on_part.string(), true});
    const run::RunSummary piece_run = run::run_static(piece, {on_piece.string(), true});
    ASSERT_EQ(config.loading.factors.size(), 3U);
    ASSERT_EQ(part_run.checkpoint_increment, 2);
    ASSERT_EQ(piece_run.checkpoint_increment, 2);
    const auto& at_checkpoint = part_run.history[1];
    ASSERT_GT(at_checkpoint.bonds_broken + at_checkpoint.damaged_points + at_checkpoint.alpha_balls, 0U);
    if (config.adaptivity.enabled) {  // α grew before the checkpoint and after it, bonds failed after it
      ASSERT_GT(at_checkpoint.alpha_balls, 0U);
      ASSERT_GT(part_run.history.back().alpha_balls, at_checkpoint.alpha_balls);
      ASSERT_GT(part_run.history.back().bonds_broken, at_checkpoint.bonds_broken);
    }
    testing::expect_same_fracture_run(piece_run, part_run, bitwise);
    const int last = static_cast<int>(config.loading.factors.size());
    const run::RunSummary part_then_piece = continued(piece, on_part, root / name / "part_then_piece", last);
    const run::RunSummary piece_then_part = continued(part, on_piece, root / name / "piece_then_part", last);
    const run::RunSummary piece_then_piece =
        continued(piece, on_piece, root / name / "piece_then_piece", last);
    for (const auto* r : {&part_then_piece, &piece_then_part, &piece_then_piece}) {
      ASSERT_EQ(r->restarted_after, 2);
      ASSERT_EQ(r->checkpoint_increment, last);
    }
    {
      SCOPED_TRACE("parts' checkpoint continued on pieces");
      testing::expect_same_fracture_run(part_then_piece, piece_run, bitwise);
    }
    {
      SCOPED_TRACE("pieces' checkpoint continued on parts");
      testing::expect_same_fracture_run(piece_then_part, part_run, bitwise);
    }
    {
      SCOPED_TRACE("pieces' checkpoint continued on pieces");
      testing::expect_same_fracture_run(piece_then_piece, piece_run, bitwise);
    }
    if (!bitwise) continue;
    // What the checkpoints hold (failed bonds in order, D per cell, held
    // dofs, K, A, output positions) is the same bytes, but for wall times:
    // the pieces' and the parts' after increment 2, and after the last
    // those of the continued runs, on pieces and on parts.
    const std::string basename = fs::path(part_run.checkpoint_path).filename().string();
    const std::string written = checkpoint_bytes(part_run.checkpoint_path);
    ASSERT_FALSE(written.empty());
    EXPECT_TRUE(checkpoint_bytes(piece_run.checkpoint_path) == written) << "after increment 2";
    const std::string then = checkpoint_bytes(piece_then_part.checkpoint_path);
    ASSERT_FALSE(then.empty());
    EXPECT_TRUE(checkpoint_bytes(part_then_piece.checkpoint_path) == then) << "parts then pieces";
    EXPECT_TRUE(checkpoint_bytes(piece_then_piece.checkpoint_path) == then) << "pieces then pieces";
  }
}

// Runs with bond failure or local damage on the pieces against the runs on
// the parts, and a checkpoint written after bonds failed, parts were held or
// damage grew, on the parts and on the pieces, continued on the other and on
// its own: the plate cut through in its band (a floating part, cells with
// motions held: the held dofs written as whole dofs, read back as dof
// names), the fracture plate (its crack started, more bonds failing after
// the checkpoint), and the damage handover plate without its adaptive α
// (damage alone, and damage with bonds that fail where it is critical:
// each change of d gathered in whole-model points, the history of every
// cell of a piece kept), all solved directly. Each run gives the run on the
// parts' records (counts, energies, damage, crack area, iterations) and
// failed-bond positions: the same bits on 2 processes, within 1e-10 on 3
// (where the direct solve's sums come in another order, also after a
// restart).
TEST(PieceCheckpoint, RunsWithFailedBondsOrDamageContinueOnPartsAndPieces) {
  const int processes = la::world_size();
  if (processes == 1) GTEST_SKIP() << "one process runs on the whole model";
  auto plate = testing::plate_cut_in_band();
  plate.loading.factors = {0.5, 0.75, 1.0};
  // A direct solve: a Krylov solve's preconditioner, kept across solves, is
  // rebuilt on restart (run/checkpoint.hpp), which moves u at round-off.
  plate.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
  auto fracture_plate =
      casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) + "/examples/fracture_plate_2d/case.toml");
  // Its first two increments (451 bonds fail in the second), then λ = 0.07:
  // 448 more (at its third, 0.1, 37 369 more, which made the test take 545 s
  // of its 600 under AddressSanitizer).
  fracture_plate.loading.factors = {1.0 / 30, 2.0 / 30, 0.07};
  auto damaged = testing::handover_plate(3);
  damaged.adaptivity.enabled = false;
  damaged.fracture.enabled = false;
  auto damaged_with_bonds = testing::handover_plate(3);
  damaged_with_bonds.adaptivity.enabled = false;
  damaged_with_bonds.alpha = testing::pulled_case(2, {}, 2.5e-3).alpha;
  // λ = 1.05 at the third: 6 bonds fail (at its own 1.2, 1 324, which took 113 s of the
  // test's 165 under AddressSanitizer on an idle machine).
  damaged_with_bonds.loading.factors = {0.4, 0.8, 1.05};
  expect_continued_alike(
      {{"plate cut free", plate},
       {"fracture plate", fracture_plate},
       {"damaged plate", damaged},
       {"damaged plate with bonds", damaged_with_bonds}},
      fs::temp_directory_path() / ("perimorph_piece_checkpoint_fracture_" + std::to_string(processes)));
}

// The same for runs whose α grows (setup::rebuild_piece_for_alpha: each
// piece rebuilt from its part, with a larger halo): the damage handover
// plate (α grown where the damage is critical, bonds failing there) and the
// flagship, the plate with a hole (α placed by the predictor before the
// checkpoint, grown from failed bonds after it), the checkpoint of a grown α
// continued on a piece rebuilt for it. The same balls, dofs, DG and
// non-local cells and energy of the model's change besides.
TEST(PieceCheckpoint, RunsWithAdaptiveAlphaContinueOnPartsAndPieces) {
  const int processes = la::world_size();
  if (processes == 1) GTEST_SKIP() << "one process runs on the whole model";
  auto hole_plate =
      casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) + "/examples/hole_plate_2d/case.toml");
  hole_plate.loading.factors = {0.4, 0.64, 0.68};
  hole_plate.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
  // The handover plate at λ = 0.7, 0.8, 0.9: damage and α grown before the
  // checkpoint, α grown again and 53 bonds failed after it (its own λ = 0.4,
  // 0.8, 1.2, 19 640 failed bonds at the third, made the test take 690 s of
  // its 900 under AddressSanitizer in CI).
  auto handover_plate = testing::handover_plate(3);
  handover_plate.loading.factors = {0.7, 0.8, 0.9};
  expect_continued_alike(
      {{"handover plate", handover_plate}, {"hole plate", hole_plate}},
      fs::temp_directory_path() / ("perimorph_piece_checkpoint_adaptive_" + std::to_string(processes)));
}

// The same for B7's block, whose crack runs on one side: at its first
// rebuild one piece of two holds no failed bond (PartSupport::rebind asked
// its own piece whether any bond had failed, and the pieces waited on each
// other: this test hung).
TEST(PieceCheckpoint, ACrackOnOnePieceContinuesOnPartsAndPieces) {
  const int processes = la::world_size();
  if (processes == 1) GTEST_SKIP() << "one process runs on the whole model";
  auto block = casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) +
                                         "/examples/b7_adaptive_block_3d/case.toml");
  // Its increments 8 to 10: 18 bonds fail and α grows in the ninth, 250
  // more and α again in the tenth.
  block.loading.factors = {8.0 / 60, 9.0 / 60, 10.0 / 60};
  block.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
  expect_continued_alike(
      {{"adaptive block", block}},
      fs::temp_directory_path() / ("perimorph_piece_checkpoint_block_" + std::to_string(processes)));
}

}  // namespace
}  // namespace perimorph
