// A run on each process's piece of the model (issue 17, step 5) under
// mpiexec -n 1, 2 and 3: run::process_model cuts an elastic case's model
// (assembled, or matrix-free) to the process's piece (the whole model on one
// process), and run_static on the pieces gives the run on the processes'
// parts of the whole model: the same CSV records, the same VTU pieces byte
// for byte (each cell's whole-mesh number in its `cell` array), and u, held
// at the piece's nodes only, the part's whole u there. A piece's checkpoint
// is written in the whole model's numbering (system::WholeNumbering): runs on
// parts and on pieces continue each other's.

#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/whole_numbering.hpp"
#include "support/model_cases.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace perimorph {
namespace {

namespace fs = std::filesystem;

/// The bytes of a file ("" if it cannot be read).
std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

/// Compares two runs' values: the same bits on 1 and 2 processes; from 3 an
/// iterative solver's preconditioner may sum other processes' messages in
/// arrival order (distributed-runs.md), so within 1e-10 of `scale` (an
/// array's largest magnitude: a component that is zero up to round-off has
/// no scale of its own).
struct SameAnswer {
  bool bitwise = la::world_size() <= 2;
  void operator()(double mine, double theirs, double scale, const char* what) const {
    if (bitwise)
      EXPECT_TRUE(same_bits(mine, theirs)) << what << ": " << mine << " against " << theirs;
    else
      EXPECT_NEAR(mine, theirs, 1e-10 * scale) << what;
  }
  void operator()(const run::IncrementRecord& a, const run::IncrementRecord& b) const {
    EXPECT_EQ(a.increment, b.increment);
    (*this)(a.strain_energy, b.strain_energy, std::abs(b.strain_energy), "strain energy");
    (*this)(a.external_work, b.external_work, std::abs(b.external_work), "external work");
    ASSERT_EQ(a.reactions.size(), b.reactions.size());
    double largest = 0.0;
    for (const Vec3& r : b.reactions) largest = std::max(largest, r.cwiseAbs().maxCoeff());
    for (std::size_t k = 0; k < a.reactions.size(); ++k)
      for (int d = 0; d < 3; ++d) (*this)(a.reactions[k][d], b.reactions[k][d], largest, "reaction");
    EXPECT_LE(std::abs(a.iterations - b.iterations), bitwise ? 0 : 1);
  }
};

/// The loaded cases made elastic (the flagship without its bond failure and
/// adaptive α), in two increments, with a VTU of each.
std::vector<testing::NamedCase> elastic_cases() {
  auto cases = testing::loaded_model_cases();
  // The matrix-free operator (DG degree 0, α ≡ 1): its piece holds the cells
  // within its bond reach, its window the box of them.
  auto grid = testing::box_case(3, {12, 8, 6}, Vec3(12.0, 8.0, 6.0), 200.0, 0.25);
  testing::add_nonlocal(grid, casefile::KernelKind::pmb, 2.6, 0.0, 1,
                        casefile::Discretization::discontinuous_constant);
  grid.alpha.value = 1.0;
  grid.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmin", 2),
                    testing::fixed("xmax", 0, 0.12)};
  grid.solver.rtol = 1e-12;
  grid.solver.op = casefile::SolverOperator::matrix_free;
  cases.push_back({"matrix-free grid", grid});
  for (auto& c : cases) {
    c.config.fracture.enabled = false;
    c.config.adaptivity.enabled = false;
    c.config.loading.factors = {0.5, 1.0};
    c.config.output.vtu = true;
    c.config.output.every = 1;
    c.config.output.checkpoint_every = 0;
  }
  return cases;
}

TEST(PieceRun, GivesTheRunOnThePartsBitForBit) {
  const fs::path root =
      fs::temp_directory_path() / ("perimorph_piece_run_" + std::to_string(la::world_size()));
  if (la::world_rank() == 0) fs::remove_all(root);
  (void)la::any_over_processes(false);  // every process waits for the folder to be cleared
  for (const auto& [name, config] : elastic_cases()) {
    SCOPED_TRACE(name);
    const std::string stem = name.substr(0, name.find(' '));
    const run::RunOptions on_part{(root / stem / "part").string(), true},
        on_piece{(root / stem / "piece").string(), true};
    // This process's part of the whole model, as a run built it before it went on pieces.
    const setup::Discretization part = run::process_part(config);
    const setup::Discretization piece = run::process_model(config);
    ASSERT_EQ(piece.piece != nullptr, la::world_size() > 1) << "cut to pieces on several processes only";
    if (!piece.piece) continue;
    const run::RunSummary expected = run::run_static(part, on_part);
    const run::RunSummary got = run::run_static(piece, on_piece);

    EXPECT_EQ(got.dofs, expected.dofs);
    EXPECT_EQ(got.dofs, part.dofmap.num_dofs());
    ASSERT_EQ(got.history.size(), 2U);
    ASSERT_EQ(got.history.size(), expected.history.size());
    // The same matrix, right-hand side and numbering.
    const SameAnswer expect_same;
    const bool bitwise = expect_same.bitwise;
    for (std::size_t i = 0; i < got.history.size(); ++i) expect_same(got.history[i], expected.history[i]);
    // u as long as the piece, the part's u at the piece's nodes.
    ASSERT_EQ(got.displacement.size(), static_cast<std::size_t>(piece.dofmap.num_dofs()));
    ASSERT_EQ(expected.displacement.size(), static_cast<std::size_t>(part.dofmap.num_dofs()));
    const int bs = part.dim();
    double largest = 0.0;
    for (double v : expected.displacement)
      if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
    // At the nodes the piece reads (setup::nodes_read; the matrix-free
    // operator's halo is its own, gathered by its product).
    std::vector<char> read(static_cast<std::size_t>(piece.dofmap.num_nodes()), 0);
    for (Index n : setup::nodes_read(piece)) read[static_cast<std::size_t>(n)] = 1;
    std::size_t nodes_compared = 0;
    for (Index c = 0; c < piece.mesh.num_cells(); ++c) {
      const auto nodes = piece.dofmap.cell_nodes(c);
      const auto whole = part.dofmap.cell_nodes(piece.piece->global_cell[static_cast<std::size_t>(c)]);
      for (std::size_t a = 0; a < nodes.size(); ++a) {
        if (!read[static_cast<std::size_t>(nodes[a])]) continue;
        ++nodes_compared;
        for (int k = 0; k < bs; ++k)
          expect_same(got.displacement[static_cast<std::size_t>(nodes[a] * bs + k)],
                      expected.displacement[static_cast<std::size_t>(whole[a] * bs + k)], largest, "u");
      }
    }
    EXPECT_GE(nodes_compared, static_cast<std::size_t>(piece.piece->dofs.num_owned()));
    // Each process's VTU pieces (and process 0's indexes) byte for byte.
    if (!bitwise) continue;
    const std::string rank = "_p" + std::to_string(la::world_rank()) + ".vtu";
    int compared = 0;
    for (const auto& entry : fs::directory_iterator(on_part.output_directory)) {
      const std::string file = entry.path().filename().string();
      const bool mine = file.ends_with(rank) ||
                        (la::world_rank() == 0 && (file.ends_with(".pvtu") || file.ends_with(".pvd")));
      if (!mine) continue;
      const std::string theirs = bytes_of(entry.path());
      EXPECT_FALSE(theirs.empty()) << file;
      EXPECT_TRUE(bytes_of(fs::path(on_piece.output_directory) / file) == theirs) << file;
      ++compared;
    }
    EXPECT_GE(compared, la::world_rank() == 0 ? 5 : 2) << "VTU pieces (and the indexes) of both increments";
  }
}

// A piece's whole numbering names each of its dofs by the whole model's dof
// map (its part's, built on the whole mesh), and gathers owned values into
// the whole vector in that order.
TEST(PieceRun, WholeNumberingIsTheWholeDofMaps) {
  for (const auto& [name, config] : elastic_cases()) {
    SCOPED_TRACE(name);
    const setup::Discretization part = run::process_part(config);
    const setup::Discretization piece = run::process_model(config);
    if (!piece.piece) continue;
    const int bs = piece.dim();
    const system::WholeNumbering whole(piece.piece->dofs, bs);
    ASSERT_EQ(whole.whole_dofs(), part.dofmap.num_dofs());
    std::vector<double> at_local(static_cast<std::size_t>(piece.dofmap.num_dofs()), -1.0);
    for (Index c = 0; c < piece.mesh.num_cells(); ++c) {
      const auto nodes = piece.dofmap.cell_nodes(c);
      const auto theirs = part.dofmap.cell_nodes(piece.piece->global_cell[static_cast<std::size_t>(c)]);
      ASSERT_EQ(nodes.size(), theirs.size());
      for (std::size_t a = 0; a < nodes.size(); ++a)
        for (int k = 0; k < bs; ++k) {
          const Index mine = nodes[a] * bs + k, expected = theirs[a] * bs + k;
          ASSERT_EQ(whole.whole_dofs_of(std::vector<Index>{mine}), std::vector<Index>{expected});
          ASSERT_EQ(whole.piece_dofs_of(std::vector<Index>{expected}), std::vector<Index>{mine});
          at_local[static_cast<std::size_t>(mine)] = static_cast<double>(expected);
        }
    }
    // Each process's owned values (their whole numbers), gathered whole: 0, 1, 2, …
    std::vector<double> owned;
    for (std::size_t n = 0; n < piece.piece->dofs.key.size(); ++n)
      if (piece.piece->dofs.owned[n])
        for (int k = 0; k < bs; ++k)
          owned.push_back(at_local[n * static_cast<std::size_t>(bs) + static_cast<std::size_t>(k)]);
    const std::vector<double> gathered = whole.whole(owned);
    for (std::size_t i = 0; i < gathered.size(); ++i) ASSERT_EQ(gathered[i], static_cast<double>(i));
    EXPECT_EQ(whole.piece_of(gathered), at_local);
    EXPECT_EQ(whole.owned_of(gathered), owned);
  }
}

// A checkpoint of a run on pieces is written in the whole model's numbering
// (system::WholeNumbering), as a run on parts writes it: each continues the
// other. The mixed CG/DG plate and the matrix-free grid, in three
// increments, a checkpoint after the second; the run on pieces
// continued from the parts' checkpoint, and the run on parts from the pieces',
// give the uninterrupted run's third increment and u.
TEST(PieceRun, CheckpointsContinueOnPartsAndPieces) {
  const fs::path root =
      fs::temp_directory_path() / ("perimorph_piece_checkpoint_" + std::to_string(la::world_size()));
  if (la::world_rank() == 0) fs::remove_all(root);
  (void)la::any_over_processes(false);  // every process waits for the folder to be cleared
  for (auto [name, config] : elastic_cases()) {
    // CG and DG nodes' keys (the mixed plate), and a matrix-free system (no matrix saved).
    if (name != "mixed CG/DG plate pulled" && name != "matrix-free grid") continue;
    SCOPED_TRACE(name);
    const std::string stem = name.substr(0, name.find(' '));
    config.loading.factors = {0.25, 0.5, 1.0};
    config.output.checkpoint_every = 2;
    const setup::Discretization part = run::process_part(config);
    const setup::Discretization piece = run::process_model(config);
    if (!piece.piece) continue;  // one process: no pieces
    const fs::path on_part = root / stem / "part", on_piece = root / stem / "piece";
    const run::RunSummary whole_run = run::run_static(part, {on_part.string(), true});
    const run::RunSummary piece_run = run::run_static(piece, {on_piece.string(), true});
    ASSERT_EQ(whole_run.checkpoint_increment, 2);
    ASSERT_EQ(piece_run.checkpoint_increment, 2);
    // Each continued in a copy of the other's output.
    const fs::path part_then_piece = root / stem / "part_then_piece",
                   piece_then_part = root / stem / "piece_then_part";
    if (la::world_rank() == 0) {
      fs::copy(on_part, part_then_piece, fs::copy_options::recursive);
      fs::copy(on_piece, piece_then_part, fs::copy_options::recursive);
    }
    (void)la::any_over_processes(false);
    run::RunOptions continued{part_then_piece.string(), true};
    continued.restart = part_then_piece.string();
    const run::RunSummary a = run::run_static(piece, continued);
    continued = {piece_then_part.string(), true};
    continued.restart = piece_then_part.string();
    const run::RunSummary b = run::run_static(part, continued);
    ASSERT_EQ(a.restarted_after, 2);
    ASSERT_EQ(b.restarted_after, 2);
    const SameAnswer expect_same;
    ASSERT_FALSE(a.history.empty());
    ASSERT_FALSE(b.history.empty());
    expect_same(a.history.back(), whole_run.history.back());
    expect_same(b.history.back(), whole_run.history.back());
    expect_same(piece_run.history.back(), whole_run.history.back());
    // u: on the parts whole-length, on the pieces the piece's.
    ASSERT_EQ(b.displacement.size(), whole_run.displacement.size());
    ASSERT_EQ(a.displacement.size(), piece_run.displacement.size());
    double largest = 0.0;
    for (double v : whole_run.displacement)
      if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
    for (std::size_t k = 0; k < b.displacement.size(); ++k)
      if (std::isfinite(whole_run.displacement[k]))
        expect_same(b.displacement[k], whole_run.displacement[k], largest, "u continued on parts");
    for (std::size_t k = 0; k < a.displacement.size(); ++k)
      if (std::isfinite(piece_run.displacement[k]))
        expect_same(a.displacement[k], piece_run.displacement[k], largest, "u continued on pieces");
  }
}

}  // namespace
}  // namespace perimorph
