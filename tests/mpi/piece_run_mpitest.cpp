// A run on each process's piece of the model (issue 17, step 5) under
// mpiexec -n 1, 2 and 3: run::process_model cuts an elastic case's model
// (assembled, or matrix-free) to the process's piece (the whole model on one
// process), and run_static on the pieces gives the run on the processes'
// parts of the whole model: the same CSV records, the same VTU pieces byte
// for byte (each cell's whole-mesh number in its `cell` array), and u, held
// at the piece's nodes only, the part's whole u there.

#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
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
    ASSERT_TRUE(run::runs_on_pieces(part, on_piece));
    const setup::Discretization piece = run::process_model(config, on_piece);
    ASSERT_EQ(piece.piece != nullptr, la::world_size() > 1) << "cut to pieces on several processes only";
    if (!piece.piece) continue;
    const run::RunSummary expected = run::run_static(part, on_part);
    const run::RunSummary got = run::run_static(piece, on_piece);

    EXPECT_EQ(got.dofs, expected.dofs);
    EXPECT_EQ(got.dofs, part.dofmap.num_dofs());
    ASSERT_EQ(got.history.size(), 2U);
    ASSERT_EQ(got.history.size(), expected.history.size());
    // The same matrix, right-hand side and numbering: the same bits on 1 and
    // 2 processes; from 3 an iterative solver's preconditioner may sum other
    // processes' messages in arrival order (distributed-runs.md).
    // Within 1e-10 of `scale`: an array's largest magnitude (a component that
    // is zero up to round-off has no scale of its own).
    const bool bitwise = la::world_size() <= 2;
    auto expect_same = [&](double mine, double theirs, double scale, const char* what) {
      if (bitwise)
        EXPECT_TRUE(same_bits(mine, theirs)) << what << ": " << mine << " against " << theirs;
      else
        EXPECT_NEAR(mine, theirs, 1e-10 * scale) << what;
    };
    for (std::size_t i = 0; i < got.history.size(); ++i) {
      const auto &a = got.history[i], &b = expected.history[i];
      expect_same(a.strain_energy, b.strain_energy, std::abs(b.strain_energy), "strain energy");
      expect_same(a.external_work, b.external_work, std::abs(b.external_work), "external work");
      ASSERT_EQ(a.reactions.size(), b.reactions.size());
      double largest = 0.0;
      for (const Vec3& r : b.reactions) largest = std::max(largest, r.cwiseAbs().maxCoeff());
      for (std::size_t k = 0; k < a.reactions.size(); ++k)
        for (int d = 0; d < 3; ++d) expect_same(a.reactions[k][d], b.reactions[k][d], largest, "reaction");
      EXPECT_LE(std::abs(a.iterations - b.iterations), bitwise ? 0 : 1);
    }
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

}  // namespace
}  // namespace perimorph
