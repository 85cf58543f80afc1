// A restart on pieces of the model reads, of a checkpoint's matrices, the
// rows of its owned dofs only (system::WholeNumbering::piece_of on a
// StoredMatrix, left in the mapped file's bytes): the rows are the whole
// model's, bit for bit, the others are never read, and a bad row of its own
// is refused with a message, on every process (issue 17; under mpiexec -n 2
// and 3).

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/stiffness.hpp"
#include "perimorph/system/whole_numbering.hpp"
#include "support/model_cases.hpp"
#include "support/owned_rows.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace perimorph {
namespace {

/// `r` as a checkpoint stores it, and read back in place.
struct Stored {
  std::string bytes;
  system::StoredMatrix matrix;
  explicit Stored(const la::Matrix::Replicated& r) {
    core::BinaryWriter out([&](std::string_view b) { bytes.append(b); });
    out.put<int>(r.pattern.block_size);
    out.put_vector(r.pattern.row_offsets);
    out.put_vector(r.pattern.columns);
    out.put_vector(r.values);
    out.flush();
    core::BinaryReader in(bytes, "test");
    matrix.block_size = in.get<int>();
    matrix.row_offsets = in.get_stored<Index>();
    matrix.columns = in.get_stored<Index>();
    matrix.values = in.get_stored<double>();
  }
};

TEST(WholeNumbering, ReadsOnlyThePiecesRowsOfAStoredMatrix) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process runs on the whole model";
  for (const auto& [name, config] : testing::model_part_cases()) {
    SCOPED_TRACE(name);
    const setup::Discretization piece = run::process_model(config);
    ASSERT_TRUE(piece.piece != nullptr);
    const int bs = piece.dim();
    const auto distribution = system::piece_distribution(piece.piece->dofs);
    const la::Matrix K = system::assemble_stiffness(piece, distribution).K;
    const system::WholeNumbering numbering(piece.piece->dofs, bs);
    la::Matrix::Replicated whole = numbering.whole(K);
    const auto expected = testing::owned_rows(K);
    ASSERT_FALSE(expected.empty());
    EXPECT_TRUE(testing::owned_rows(la::Matrix::from_replicated(numbering.piece_of(Stored(whole).matrix),
                                                                distribution)) == expected);

    // The whole node of each owned dof node.
    std::vector<char> mine(static_cast<std::size_t>(whole.pattern.num_block_rows()), 0);
    const la::OwnedDofs owned(distribution.get(), bs, piece.dofmap.num_dofs());
    for (std::size_t j = 0; j < owned.size(); ++j) {
      const Index w = numbering.whole_dofs_of(std::vector<Index>{owned.dof(j)}).front();
      mine[static_cast<std::size_t>(w / bs)] = 1;
    }
    // Every other row spoiled: not read.
    la::Matrix::Replicated spoiled = whole;
    for (Index w = 0; w < spoiled.pattern.num_block_rows(); ++w)
      if (!mine[static_cast<std::size_t>(w)])
        for (auto k = spoiled.pattern.row_offsets[static_cast<std::size_t>(w)];
             k < spoiled.pattern.row_offsets[static_cast<std::size_t>(w) + 1]; ++k)
          spoiled.pattern.columns[static_cast<std::size_t>(k)] = -7;
    EXPECT_TRUE(testing::owned_rows(la::Matrix::from_replicated(numbering.piece_of(Stored(spoiled).matrix),
                                                                distribution)) == expected);

    // A row of its own spoiled: refused, naming it.
    const auto first_mine = static_cast<Index>(std::find(mine.begin(), mine.end(), 1) - mine.begin());
    la::Matrix::Replicated bad = whole;
    bad.pattern
        .columns[static_cast<std::size_t>(bad.pattern.row_offsets[static_cast<std::size_t>(first_mine)])] =
        bad.pattern.num_block_rows();
    try {
      (void)numbering.piece_of(Stored(bad).matrix);
      ADD_FAILURE() << "a column out of range was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "the matrix row of dof node " + std::to_string(first_mine) + " has a column out of range");
    }
    bad = whole;
    bad.pattern.row_offsets[static_cast<std::size_t>(first_mine) + 1] = -1;
    EXPECT_THROW((void)numbering.piece_of(Stored(bad).matrix), InputError);
  }
}

// A checkpoint's K with a bad row in the rows of process 1 alone: every
// process stops with an InputError (none waits for ever in the collective
// matrix creation), process 1 naming the row.
TEST(WholeNumbering, ABadRowOnOneProcessStopsEveryProcess) {
  if (la::world_size() == 1) GTEST_SKIP() << "one process runs on the whole model";
  const auto [name, config] = testing::model_part_cases().front();
  SCOPED_TRACE(name);
  const setup::Discretization piece = run::process_model(config);
  const int bs = piece.dim();
  const auto distribution = system::piece_distribution(piece.piece->dofs);
  const system::WholeNumbering numbering(piece.piece->dofs, bs);
  const system::ConstrainedSystem made(piece, system::assemble_stiffness(piece, distribution).K,
                                       setup::build_dirichlet(piece), setup::build_external_force(piece));
  std::string bytes;
  core::BinaryWriter out([&](std::string_view b) { bytes.append(b); });
  made.save(out, &numbering);
  out.flush();

  // Process 1's first owned dof node, in the whole numbering.
  const la::OwnedDofs owned(distribution.get(), bs, piece.dofmap.num_dofs());
  const Index first = numbering.whole_dofs_of(std::vector<Index>{owned.dof(0)}).front() / bs;
  const std::vector<double> firsts = la::all_gather({static_cast<double>(first)});
  const auto row = static_cast<std::size_t>(firsts.at(1));
  // "system", the block size, the row offsets (a count, then the values), the columns.
  const std::size_t tag = sizeof(std::uint64_t) + 6, offsets = tag + sizeof(int) + sizeof(std::uint64_t);
  std::uint64_t rows = 0;
  std::memcpy(&rows, bytes.data() + tag + sizeof(int), sizeof rows);
  Index at = 0;
  std::memcpy(&at, bytes.data() + offsets + row * sizeof(Index), sizeof at);
  const std::size_t columns = offsets + rows * sizeof(Index) + sizeof(std::uint64_t);
  const auto out_of_range = static_cast<Index>(rows);  // rows − 1 block rows: one past the last
  std::memcpy(bytes.data() + columns + static_cast<std::size_t>(at) * sizeof(Index), &out_of_range,
              sizeof out_of_range);

  core::BinaryReader in(bytes, "spoiled.checkpoint");
  try {
    (void)system::ConstrainedSystem::restored(piece, setup::build_dirichlet(piece),
                                              setup::build_external_force(piece), in, &numbering);
    ADD_FAILURE() << "a bad row was read";
  } catch (const InputError& e) {
    const std::string what = e.what(), named = "the matrix row of dof node " + std::to_string(row);
    if (la::world_rank() == 1)
      EXPECT_NE(what.find(named), std::string::npos) << what;
    else
      EXPECT_NE(what.find("a matrix row another process read is bad"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace perimorph
