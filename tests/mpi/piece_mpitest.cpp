// The halo numbering of issue 17, item 1, under mpiexec -n 1, 2 and 3: each
// process builds its piece of the model (its part's cells and their node
// neighbours, a mesh of their own numbered locally) and numbers the piece's
// dof nodes from the piece alone, one prefix sum and one exchange by key
// (system::piece_distribution). The numbers must be the whole model's
// (partition::dof_numbering), ghosts included, the local stiffness
// assembled on the pieces the whole model's distributed matrix bit for bit,
// and a Dirichlet problem solved on the pieces the whole model's u.

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/la/key_exchange.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/vector.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/system/piece_distribution.hpp"
#include "perimorph/system/stiffness.hpp"
#include "perimorph/system/whole_numbering.hpp"
#include "support/owned_rows.hpp"
#include "support/pieces.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cstring>
#include <tuple>

namespace perimorph {
namespace {

mesh::Mesh box(int dim) {
  return dim == 2 ? mesh::make_box({2, Vec3(0, 0, 0), Vec3(9, 7, 0), {9, 7, 1}})
                  : mesh::make_box({3, Vec3(0, 0, 0), Vec3(5, 4, 3), {5, 4, 3}});
}

/// The whole model's dof node at corner a of the piece's local cell.
Index whole_node_of(const dofs::DofMap& whole, const testing::TestPiece& piece, Index local_cell,
                    std::size_t a) {
  return whole.cell_nodes(piece.part.global_cell[static_cast<std::size_t>(local_cell)])[a];
}

class Pieces : public ::testing::TestWithParam<int> {};

TEST_P(Pieces, NumberTheirDofNodesAsTheWholeModelGhostsIncluded) {
  const auto whole = box(GetParam());
  const auto flags = testing::mixed_continuity(whole);
  const dofs::DofMap dm(whole, whole.dim(), flags);
  const int parts = la::world_size(), part = la::world_rank();
  const auto p = partition::coordinate_bisection(whole, parts);
  const auto layout = partition::dof_numbering(dm, p);
  const auto piece = testing::make_piece(whole, flags, p, part, whole.dim());
  const auto d = system::piece_distribution(piece.dofs);

  EXPECT_EQ(d->begin, layout.part_offsets[static_cast<std::size_t>(part)]);
  EXPECT_EQ(d->end, layout.part_offsets[static_cast<std::size_t>(part) + 1]);
  ASSERT_EQ(d->num_nodes(), piece.dofmap.num_nodes());
  Index ghosts = 0;
  for (Index c = 0; c < piece.dofmap.num_cells(); ++c) {
    const auto nodes = piece.dofmap.cell_nodes(c);
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      const Index w = whole_node_of(dm, piece, c, a);
      EXPECT_EQ(d->to_distributed[static_cast<std::size_t>(nodes[a])],
                layout.to_distributed[static_cast<std::size_t>(w)]);
      EXPECT_EQ(d->owns(nodes[a]), layout.node_owner[static_cast<std::size_t>(w)] == part);
    }
  }
  for (Index n = 0; n < piece.dofmap.num_nodes(); ++n) ghosts += d->owns(n) ? 0 : 1;
  if (parts > 1) {
    EXPECT_GT(ghosts, 0) << "a piece reads its neighbours' nodes";
  }
}

/// The local stiffness of the cells with a node `owns` holds for (DG degree 0
/// cells have none: purely non-local, THEORY §4), cell c's
/// tensor that of the whole model's cell global(c) (a different one a cell,
/// so that a cell mistaken for another shows).
la::Matrix assemble(const mesh::Mesh& mesh, const dofs::DofMap& dm, std::shared_ptr<const la::Distribution> d,
                    const std::function<Index(Index)>& global) {
  const auto rule = fem::gauss_legendre(mesh.dim(), 2);
  fem::ConstitutiveField C(mesh.dim(), mesh.num_cells(), static_cast<int>(rule.size()));
  for (Index c = 0; c < mesh.num_cells(); ++c) {
    const fem::IsotropicElasticity m{100.0 + global(c), 0.2 + 0.001 * (global(c) % 7)};
    C.set_cell(c,
               C.add_tensor(fem::reduce_stiffness(fem::stiffness_voigt(m), mesh.dim(), PlaneMode::strain)));
  }
  const auto owns = [&](Index n) { return d->owns(n); };
  la::Matrix K(assembly::build_sparsity(dm, nullptr, owns), d);
  const auto touching = partition::cells_touching(dm, owns);
  assembly::assemble_elasticity({mesh, dm, rule, 1.0}, C, K, [&](Index c) {
    return touching[static_cast<std::size_t>(c)] != 0 &&
           dm.continuity(c) != dofs::Continuity::discontinuous_constant;
  });
  K.finalize();
  return K;
}

using testing::owned_rows;
using testing::Rows;

TEST_P(Pieces, AssembleTheWholeModelsMatrixBitForBit) {
  const auto whole = box(GetParam());
  const auto flags = testing::mixed_continuity(whole);
  const dofs::DofMap dm(whole, whole.dim(), flags);
  const int parts = la::world_size(), part = la::world_rank();
  const auto p = partition::coordinate_bisection(whole, parts);
  const auto whole_d = system::distribution_of(partition::dof_numbering(dm, p), part);
  const auto piece = testing::make_piece(whole, flags, p, part, whole.dim());

  const Rows expected = owned_rows(assemble(whole, dm, whole_d, [](Index c) { return c; }));
  const Rows got =
      owned_rows(assemble(piece.part.mesh, piece.dofmap, system::piece_distribution(piece.dofs),
                          [&](Index c) { return piece.part.global_cell[static_cast<std::size_t>(c)]; }));
  ASSERT_FALSE(expected.empty());
  EXPECT_TRUE(got == expected) << "process " << part << " of " << parts;
}

bool same(const la::Matrix::Replicated& a, const la::Matrix::Replicated& b) {
  return a.pattern.block_size == b.pattern.block_size && a.pattern.row_offsets == b.pattern.row_offsets &&
         a.pattern.columns == b.pattern.columns &&
         std::equal(a.values.begin(), a.values.end(), b.values.begin(), b.values.end(),
                    [](double x, double y) { return std::memcmp(&x, &y, sizeof(double)) == 0; });
}

// What a checkpoint of a run on pieces gathers (run/whole_state.hpp): the
// matrix and the vectors in the whole model's numbering, every process's
// share, on every process or on process 0 alone (la::Onto::process_zero),
// where the others then hold nothing whole.
TEST_P(Pieces, GatherTheWholeMatrixAndVectorsOnEveryProcessOrOnProcessZeroAlone) {
  const auto whole = box(GetParam());
  const auto flags = testing::mixed_continuity(whole);
  const dofs::DofMap dm(whole, whole.dim(), flags);
  const int parts = la::world_size(), part = la::world_rank(), bs = whole.dim();
  const auto p = partition::coordinate_bisection(whole, parts);
  const auto whole_d = system::distribution_of(partition::dof_numbering(dm, p), part);
  const auto piece = testing::make_piece(whole, flags, p, part, bs);
  const la::Matrix K = assemble(piece.part.mesh, piece.dofmap, system::piece_distribution(piece.dofs),
                                [&](Index c) { return piece.part.global_cell[static_cast<std::size_t>(c)]; });
  const la::Matrix K_whole = assemble(whole, dm, whole_d, [](Index c) { return c; });
  const la::Matrix::Replicated expected = K_whole.replicated();
  ASSERT_FALSE(expected.values.empty());
  // The copy against the dense whole matrix (MatGetValues, not the copy's
  // code): each block row's columns ascending, every stored entry the dense
  // one, every nonzero stored.
  const Eigen::MatrixXd dense = K_whole.to_dense();
  const auto& pattern = expected.pattern;
  std::size_t at = 0;
  Index stored_nonzeros = 0;
  for (Index b = 0; b < pattern.num_block_rows(); ++b) {
    const auto cols = pattern.row(b);
    EXPECT_TRUE(std::is_sorted(cols.begin(), cols.end()) &&
                std::adjacent_find(cols.begin(), cols.end()) == cols.end())
        << "block row " << b;
    for (int k = 0; k < bs; ++k)
      for (Index c : cols)
        for (int l = 0; l < bs; ++l, ++at) {
          EXPECT_EQ(expected.values[at], dense(b * bs + k, c * bs + l)) << "row " << b * bs + k;
          stored_nonzeros += expected.values[at] != 0.0 ? 1 : 0;
        }
  }
  EXPECT_EQ(stored_nonzeros, (dense.array() != 0.0).count());

  const system::WholeNumbering every(piece.dofs, bs), zero(piece.dofs, bs, la::Onto::process_zero);
  EXPECT_TRUE(same(every.whole(K), expected)) << "process " << part;
  const la::Matrix::Replicated on_zero = zero.whole(K);
  // Each owned dof's value its name (key × bs + component): the whole vector
  // holds at whole dof w the name of w.
  std::vector<double> owned;
  for (std::size_t n = 0; n < piece.dofs.key.size(); ++n)
    if (piece.dofs.owned[n])
      for (int k = 0; k < bs; ++k) owned.push_back(static_cast<double>(piece.dofs.key[n] * bs + k));
  const std::vector<double> v = every.whole(owned), v_zero = zero.whole(owned);
  ASSERT_EQ(static_cast<Index>(v.size()), dm.num_dofs());
  for (Index w = 0; w < dm.num_dofs(); ++w) {
    EXPECT_EQ(v[static_cast<std::size_t>(w)], static_cast<double>(every.name_of_whole(w)))
        << "whole dof " << w;
    EXPECT_EQ(every.whole_of_name(every.name_of_whole(w)), w);
  }
  if (part == 0) {
    EXPECT_TRUE(same(on_zero, expected));
    EXPECT_EQ(v_zero, v);
    EXPECT_EQ(zero.whole_dofs(), every.whole_dofs());
  } else {
    EXPECT_TRUE(on_zero.values.empty() && on_zero.pattern.columns.empty() &&
                on_zero.pattern.row_offsets.size() == 1)
        << "process " << part << " holds a whole matrix";
    EXPECT_TRUE(v_zero.empty()) << "process " << part << " holds a whole vector";
    EXPECT_EQ(zero.whole_dofs(), 0);
  }
}

/// u of K u = f with u_x = 0.05 on xmax and u = 0 on xmin (the mesh's node
/// sets, on a piece its nodes of them), solved by CG + GAMG with the nodes'
/// coordinates for the rigid-body modes, then u at every node of the dof map
/// (NodeGather: the piece's nodes only, or the whole model's).
std::vector<double> solve(const mesh::Mesh& mesh, const dofs::DofMap& dm,
                          std::shared_ptr<const la::Distribution> d,
                          const std::function<Index(Index)>& global) {
  la::Matrix K = assemble(mesh, dm, d, global);
  const int bs = dm.block_size();
  std::vector<Index> fixed, pulled;
  for (Index n : dm.dof_nodes_of_mesh_nodes(mesh.node_sets.at("xmin")))
    for (int k = 0; k < bs; ++k) fixed.push_back(n * bs + k);
  for (Index n : dm.dof_nodes_of_mesh_nodes(mesh.node_sets.at("xmax"))) pulled.push_back(n * bs);
  la::Vector x(d, bs), rhs(d, bs), u(d, bs);
  x.set_at(pulled, 0.05);
  std::vector<Index> rows = fixed;
  rows.insert(rows.end(), pulled.begin(), pulled.end());
  K.eliminate_dirichlet(rows, x, rhs);
  K.set_spd();
  la::LinearSolver solver(1e-12, 1000);
  solver.set_operator(
      K, [&](Index n) { return dm.node_coordinate(mesh, n); }, mesh.dim());
  const auto report = solver.solve(rhs, u);
  EXPECT_LT(report.relative_residual, 1e-11) << report.iterations << " iterations";
  la::NodeGather gather(d, bs, {});
  return gather.gathered(u, std::nan(""));
}

TEST_P(Pieces, SolveADirichletProblemAsTheWholeModelHoldingUAtTheirNodesOnly) {
  const auto whole = box(GetParam());
  const std::vector<dofs::Continuity> cg(static_cast<std::size_t>(whole.num_cells()),
                                         dofs::Continuity::continuous);
  const dofs::DofMap dm(whole, whole.dim(), cg);
  const int parts = la::world_size(), part = la::world_rank();
  const auto p = partition::coordinate_bisection(whole, parts);
  const auto whole_d = system::distribution_of(partition::dof_numbering(dm, p), part);
  const auto piece = testing::make_piece(whole, cg, p, part, whole.dim());

  const auto expected = solve(whole, dm, whole_d, [](Index c) { return c; });
  const auto got = solve(piece.part.mesh, piece.dofmap, system::piece_distribution(piece.dofs),
                         [&](Index c) { return piece.part.global_cell[static_cast<std::size_t>(c)]; });
  const int bs = whole.dim();
  ASSERT_EQ(got.size(), static_cast<std::size_t>(piece.dofmap.num_nodes() * bs)) << "u as long as the piece";
  // The same matrix, right-hand side and layout: the same bits on 1 and 2
  // processes; from 3, GAMG sums other processes' messages in arrival order
  // (distributed-runs.md, "Run after run"), so within round-off.
  double largest = 0.0, diff = 0.0;
  for (Index c = 0; c < piece.dofmap.num_cells(); ++c) {
    const auto nodes = piece.dofmap.cell_nodes(c);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int k = 0; k < bs; ++k) {
        const double mine = got[static_cast<std::size_t>(nodes[a] * bs + k)];
        const double theirs = expected[static_cast<std::size_t>(whole_node_of(dm, piece, c, a) * bs + k)];
        if (parts <= 2) {
          EXPECT_EQ(std::memcmp(&mine, &theirs, sizeof(double)), 0) << mine << " against " << theirs;
        }
        diff = std::max(diff, std::abs(mine - theirs));
        largest = std::max(largest, std::abs(theirs));
      }
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(diff, 1e-12) << "process " << part << " of " << parts;
}

INSTANTIATE_TEST_SUITE_P(Dim, Pieces, ::testing::Values(2, 3));

TEST(ValuesOfKeys, EveryProcessGetsTheValuesOfTheKeysItAsksFromTheirHolders) {
  const int size = la::world_size(), rank = la::world_rank();
  // Process r holds the keys 10 k + r (k < 5) with value 1000 r + k, and asks
  // for every key of the next process in reverse order.
  std::vector<Index> keys, values, wanted;
  for (Index k = 0; k < 5; ++k) {
    keys.push_back(10 * k + rank);
    values.push_back(1000 * rank + k);
  }
  const int next = (rank + 1) % size;
  if (next != rank)
    for (Index k = 4; k >= 0; --k) wanted.push_back(10 * k + next);
  const auto got = la::values_of_keys(keys, values, wanted, 10 * 5);
  ASSERT_EQ(got.size(), wanted.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], 1000 * next + (4 - static_cast<Index>(i)));
  EXPECT_EQ(la::offset_over_processes(rank + 1), rank * (rank + 1) / 2);
}

TEST(ValuesOfKeys, AKeyNoProcessHoldsStopsEveryProcess) {
  const int rank = la::world_rank();
  const std::vector<Index> keys{2 * rank}, values{rank};
  // Process 0 asks for an odd key, which nobody holds.
  const std::vector<Index> wanted = rank == 0 ? std::vector<Index>{1} : std::vector<Index>{};
  EXPECT_THROW(la::values_of_keys(keys, values, wanted, 2 * la::world_size()), Error);
}

// la::exchange: each process sends a parcel to the next two processes (one
// empty, not sent, to the second on odd ranks); each receives from the right
// senders, in rank order, exactly what they sent. On one process nothing.
TEST(Exchange, DeliversEachParcelToItsProcessOnly) {
  const int rank = la::world_rank(), size = la::world_size();
  std::vector<la::Parcel> out;
  for (int step : {1, 2}) {
    const int to = (rank + step) % size;
    if (to == rank ||
        std::any_of(out.begin(), out.end(), [&](const la::Parcel& p) { return p.process == to; }))
      continue;
    la::Parcel p{to, {}};
    if (step == 1 || rank % 2 == 0)
      for (int k = 0; k <= rank; ++k) p.values.push_back(100.0 * rank + 10.0 * step + k);
    out.push_back(std::move(p));
  }
  const std::vector<la::Parcel> in = la::exchange(out);
  std::vector<la::Parcel> expected;
  for (int from = 0; from < size; ++from)
    for (int step : {1, 2}) {
      if (from == rank || (from + step) % size != rank) continue;
      if (step == 2 && (from + 1) % size == rank) continue;  // the sender sent one parcel here
      if (step == 2 && from % 2 == 1) continue;              // empty: not sent
      la::Parcel p{from, {}};
      for (int k = 0; k <= from; ++k) p.values.push_back(100.0 * from + 10.0 * step + k);
      expected.push_back(std::move(p));
    }
  ASSERT_EQ(in.size(), expected.size()) << "process " << rank;
  for (std::size_t k = 0; k < in.size(); ++k) {
    EXPECT_EQ(in[k].process, expected[k].process);
    EXPECT_EQ(in[k].values, expected[k].values) << "from " << in[k].process;
  }
  // The others' lists on process 0 only, in rank order; the largest value everywhere.
  const std::vector<double> zero = la::gather_on_process_zero({static_cast<double>(rank), 0.5});
  if (rank == 0) {
    ASSERT_EQ(zero.size(), 2U * static_cast<std::size_t>(size));
    for (int r = 0; r < size; ++r) EXPECT_EQ(zero[2 * static_cast<std::size_t>(r)], r);
  } else {
    EXPECT_TRUE(zero.empty());
  }
  EXPECT_EQ(la::largest_over_processes(-1.0 - rank), -1.0);
}

}  // namespace
}  // namespace perimorph
