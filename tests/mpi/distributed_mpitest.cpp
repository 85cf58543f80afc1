// Distributed assembly and solve (issue 17), run under mpiexec -n 1, 2 and 3
// (tests/cli/mpi_tests.cmake): every process builds the same model and the
// same partition (coordinate bisection into as many parts as processes),
// assembles the rows of the nodes it owns into a matrix spread over the
// processes (owner computes), and the result must be the serial one: the
// matrix bit for bit, and the displacement of a Dirichlet-driven solve within
// the solver's tolerance.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/sparsity.hpp"
#include "perimorph/bonds/broken_bonds.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/la/shell_matrix.hpp"
#include "perimorph/partition/dof_layout.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <Eigen/Cholesky>

#include <cmath>
#include <cstdio>
#include <limits>

namespace perimorph {
namespace {

/// testing::mixed_cg_dg_plate, held at x = 0 and pulled at x = 12.
casefile::CaseConfig mixed_plate() {
  auto c = testing::mixed_cg_dg_plate();
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmax", 0, 0.05)};
  return c;
}

/// A 3D hybrid bar, CG everywhere, α ≡ 1 about its middle.
casefile::CaseConfig hybrid_bar() {
  auto c = testing::box_case(3, {10, 4, 3}, Vec3(2.5, 1.0, 0.75), 90.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::exponential, 0.4, 0.1, 2);
  c.alpha.regions = {testing::alpha_ball(Vec3(1.25, 0.5, 0.375), 0.4, 0.3)};
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmin", 2),
                 testing::fixed("xmax", 0, 0.01)};
  return c;
}

std::shared_ptr<const la::Distribution> distribute(const setup::Discretization& m) {
  const auto p = partition::coordinate_bisection(m.mesh, la::world_size());
  return system::distribution_of(partition::dof_layout(m.dofmap, p, m.nonlocal->graph), la::world_rank());
}

Eigen::MatrixXd serial_stiffness(const setup::Discretization& m) {
  testing::DenseInserter K(m.dofmap.num_dofs());
  assembly::assemble_elasticity(m.local_space(), m.stiffness, K);
  assembly::assemble_nonlocal(m.nonlocal_space(), K);
  return K.A;
}

class Distributed2D3D : public ::testing::TestWithParam<int> {
 protected:
  casefile::CaseConfig config() const { return GetParam() == 2 ? mixed_plate() : hybrid_bar(); }
};

TEST_P(Distributed2D3D, AssembledMatrixEqualsTheSerialOne) {
  const auto m = setup::build_discretization(config());
  const auto d = distribute(m);
  const auto K = system::assemble_stiffness(m, d);
  EXPECT_EQ(K.K.rows(), m.dofmap.num_dofs());  // the global size
  const Eigen::MatrixXd serial = serial_stiffness(m), distributed = K.K.to_dense();
  ASSERT_EQ(serial.rows(), distributed.rows());
  EXPECT_GT(serial.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE((serial.array() == distributed.array()).all())
      << "bit for bit; max difference " << (serial - distributed).cwiseAbs().maxCoeff();
}

TEST_P(Distributed2D3D, DirichletSolveEqualsTheSerialOne) {
  const auto m = setup::build_discretization(config());
  const auto d = distribute(m);
  const auto bc = setup::build_dirichlet(m);
  // Serial reference: K_ff u_f = −K_fp g, by a dense Cholesky factorization.
  const Eigen::MatrixXd K = serial_stiffness(m);
  const auto n = static_cast<Index>(K.rows());
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < bc.dofs.size(); ++k) {
    fixed[static_cast<std::size_t>(bc.dofs[k])] = 1;
    g[bc.dofs[k]] = bc.values[k];
  }
  std::vector<Index> free;
  for (Index i = 0; i < n; ++i)
    if (!fixed[static_cast<std::size_t>(i)]) free.push_back(i);
  Eigen::MatrixXd Kff(free.size(), free.size());
  Eigen::VectorXd b(free.size());
  const Eigen::VectorXd Kg = K * g;
  for (std::size_t i = 0; i < free.size(); ++i) {
    b[static_cast<Eigen::Index>(i)] = -Kg[free[i]];
    for (std::size_t j = 0; j < free.size(); ++j)
      Kff(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = K(free[i], free[j]);
  }
  const Eigen::VectorXd uf = Kff.llt().solve(b);
  Eigen::VectorXd serial = g;
  for (std::size_t i = 0; i < free.size(); ++i) serial[free[i]] = uf[static_cast<Eigen::Index>(i)];

  // Distributed: eliminate, solve (CG + GAMG, the default), gather.
  auto A = system::assemble_stiffness(m, d).K;
  la::Vector x(d, m.dim()), rhs(d, m.dim()), u(d, m.dim());
  x.assign_replicated(std::vector<double>(g.data(), g.data() + n));
  A.eliminate_dirichlet(bc.dofs, x, rhs);
  A.set_spd();
  la::LinearSolver solver(1e-12, 1000);
  solver.set_operator(A, m.dofmap.node_coordinate_on(m.mesh), m.dim());
  const auto report = solver.solve(rhs, u);
  EXPECT_LT(report.relative_residual, 1e-11) << report.iterations << " iterations";
  const auto got = u.to_replicated();
  ASSERT_EQ(static_cast<Index>(got.size()), n);
  double diff = 0.0;
  for (Index i = 0; i < n; ++i) diff = std::max(diff, std::abs(got[static_cast<std::size_t>(i)] - serial[i]));
  EXPECT_LT(diff, 1e-9 * serial.cwiseAbs().maxCoeff()) << "ranks " << la::world_size();
}

INSTANTIATE_TEST_SUITE_P(Dim, Distributed2D3D, ::testing::Values(2, 3));

TEST(DistributedVector, ReplicatedRoundTrip) {
  const auto m = setup::build_discretization(mixed_plate());
  const auto d = distribute(m);
  std::vector<double> values(static_cast<std::size_t>(m.dofmap.num_dofs()));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 + static_cast<double>(i);
  la::Vector v(d, m.dim());
  v.assign_replicated(values);
  EXPECT_EQ(v.to_replicated(), values);
  double sum2 = 0.0;
  for (double x : values) sum2 += x * x;
  EXPECT_NEAR(v.norm2(), std::sqrt(sum2), 1e-12 * std::sqrt(sum2));
  EXPECT_TRUE(v.all_finite());
}

TEST(DistributedVector, AddAtAndSetAtChangeTheEntriesNamedInTheAssemblyNumbering) {
  const auto m = setup::build_discretization(mixed_plate());
  const auto d = distribute(m);
  const Index n = m.dofmap.num_dofs();
  std::vector<double> expected(static_cast<std::size_t>(n), 0.0);
  la::Vector v(d, m.dim());
  const std::vector<Index> at{0, 7, n - 1, 7, n / 2};
  const std::vector<double> add{1.0, 2.0, 3.0, 4.0, 5.0};
  v.add_at(at, add);
  for (std::size_t k = 0; k < at.size(); ++k) expected[static_cast<std::size_t>(at[k])] += add[k];
  const std::vector<Index> set{n / 2, 3};
  v.set_at(set, -1.0);
  for (Index i : set) expected[static_cast<std::size_t>(i)] = -1.0;
  EXPECT_EQ(v.to_replicated(), expected);
}

TEST(DistributedShell, GetsTheWholeXAndKeepsTheOwnedRowsOfY) {
  const auto m = setup::build_discretization(mixed_plate());
  const auto d = distribute(m);
  const auto n = static_cast<std::size_t>(m.dofmap.num_dofs());
  // y_i = i · x_i + x_{n−1−i}: every row reads an entry another process may own.
  la::ShellMatrix A(d, m.dim(), [&](std::span<const double> x, std::span<double> y) {
    ASSERT_EQ(x.size(), n);
    for (std::size_t i = 0; i < n; ++i)
      if (d->owns(static_cast<Index>(i) / m.dim())) y[i] = static_cast<double>(i) * x[i] + x[n - 1 - i];
  });
  EXPECT_EQ(A.rows(), static_cast<Index>(n));
  std::vector<double> xv(n), expected(n);
  for (std::size_t i = 0; i < n; ++i) xv[i] = 1.0 + 0.5 * static_cast<double>(i);
  for (std::size_t i = 0; i < n; ++i) expected[i] = static_cast<double>(i) * xv[i] + xv[n - 1 - i];
  la::Vector x(d, m.dim()), y(d, m.dim());
  x.assign_replicated(xv);
  A.mult(x, y);
  EXPECT_EQ(y.to_replicated(), expected);

  // With the nodes it reads named (the halo), a process receives those
  // entries only, and sees 0 elsewhere: the same product.
  const Index dim = m.dim(), nodes = m.dofmap.num_nodes();
  std::vector<Index> reads;
  for (Index node = 0; node < nodes; ++node)
    if (d->owns(node) || d->owns(nodes - 1 - node)) reads.push_back(node);
  std::vector<char> is_read(static_cast<std::size_t>(nodes), 0);
  for (Index node : reads) is_read[static_cast<std::size_t>(node)] = 1;
  la::ShellMatrix H(
      d, m.dim(),
      [&](std::span<const double> xs, std::span<double> ys) {
        for (std::size_t i = 0; i < n; ++i) {
          const Index node = static_cast<Index>(i) / dim;
          EXPECT_EQ(xs[i], is_read[static_cast<std::size_t>(node)] ? xv[i] : 0.0) << "entry " << i;
          if (d->owns(node)) ys[i] = static_cast<double>(i) * xs[i] + xs[n - 1 - i];
        }
      },
      reads);
  la::Vector z(d, m.dim());
  H.mult(x, z);
  EXPECT_EQ(z.to_replicated(), expected);
  Index others = 0;
  for (Index node : reads) others += d->owns(node) ? 0 : dim;
  EXPECT_EQ(H.received_per_product(), others);
  EXPECT_EQ(A.received_per_product(), la::world_size() == 1 ? 0 : (nodes - d->owned_nodes()) * dim);
}

// What a run brings of u after each solve (la::NodeGather): the entries of
// the nodes a process reads, exact, and nothing else; a second gather with
// the same scatter brings the new values.
TEST(NodeGather, BringsTheNodesReadAndLeavesTheRest) {
  const auto m = setup::build_discretization(mixed_plate());
  const auto d = distribute(m);
  const Index dim = m.dim(), nodes = m.dofmap.num_nodes();
  const auto n = static_cast<std::size_t>(nodes * dim);
  std::vector<Index> reads;
  for (Index node = 0; node < nodes; ++node)
    if (d->owns(node) || node % 3 == 0) reads.push_back(node);
  std::vector<char> is_read(static_cast<std::size_t>(nodes), 0);
  for (Index node : reads) is_read[static_cast<std::size_t>(node)] = 1;
  la::NodeGather halo(d, dim, reads);
  la::Vector x(d, dim);
  for (double shift : {0.0, 100.0}) {
    std::vector<double> xv(n);
    for (std::size_t i = 0; i < n; ++i) xv[i] = shift + 1.0 + 0.25 * static_cast<double>(i);
    x.assign_replicated(xv);
    const std::vector<double> got = halo.gathered(x, std::numeric_limits<double>::quiet_NaN());
    ASSERT_EQ(got.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      if (is_read[i / static_cast<std::size_t>(dim)])
        EXPECT_EQ(got[i], xv[i]) << "entry " << i;
      else
        EXPECT_TRUE(std::isnan(got[i])) << "entry " << i;
    }
  }
  Index others = 0;
  for (Index node : reads) others += d->owns(node) ? 0 : dim;
  EXPECT_EQ(halo.received(), others);
  la::NodeGather every(d, dim, {});
  std::vector<double> all(n, -1.0);
  every.gather(x, all);
  EXPECT_EQ(all, x.to_replicated());
  EXPECT_EQ(every.received(), (nodes - d->owned_nodes()) * dim);
}

// What a run keeps of K u and its last recorded state (la::OwnedDofs): the
// dofs a process owns, ascending, and nothing else; the values there come
// from the vector without sending anything, and go back whole from every
// process's share.
TEST(DistributedVector, HeldAtTheOwnedDofsOnly) {
  const auto m = setup::build_discretization(mixed_plate());
  const auto d = distribute(m);
  const Index dim = m.dim();
  const Index n = m.dofmap.num_dofs();
  std::vector<double> values(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 + static_cast<double>(i % 7);
  const la::OwnedDofs owned(d.get(), dim, n);
  EXPECT_EQ(static_cast<Index>(owned.size()), d->owned_nodes() * dim);
  std::vector<char> seen(values.size(), 0);
  for (std::size_t j = 0; j < owned.size(); ++j) {
    const Index k = owned.dof(j);
    EXPECT_TRUE(d->owns(k / dim)) << "dof " << k;
    if (j > 0) {
      EXPECT_LT(owned.dof(j - 1), k);
    }
    EXPECT_EQ(owned.position(k), static_cast<std::ptrdiff_t>(j));
    seen[static_cast<std::size_t>(k)] = 1;
  }
  for (Index k = 0; k < n; ++k) {
    if (!seen[static_cast<std::size_t>(k)]) {
      EXPECT_EQ(owned.position(k), -1) << "dof " << k;
    }
  }

  la::Vector v(d, dim);
  v.assign_replicated(values);
  const std::vector<double> mine = v.at_owned(owned);
  EXPECT_EQ(mine, owned.of(values));
  la::Vector w(d, dim);
  w.assign_owned(owned, mine);
  EXPECT_EQ(w.to_replicated(), values);
  // Small integers: any order of the additions gives the same sum.
  const double sum = owned.sum(1.0, [&](std::size_t j) { return mine[j]; });
  double expected = 1.0;
  for (double x : values) expected += x;
  EXPECT_EQ(sum, expected);

  const la::OwnedDofs every(nullptr, dim, n);
  EXPECT_EQ(every.size(), values.size());
  EXPECT_EQ(every.of(values), values);
  EXPECT_EQ(every.position(n - 1), n - 1);
}

// The run's sums over the dofs (energies, reactions) add each process's
// share in rank order: the same bits on every process.
TEST(SumOverProcesses, AddsInRankOrderWithTheSameBitsOnEveryProcess) {
  const int rank = la::world_rank(), size = la::world_size();
  const auto share = [](int r) { return std::vector<double>{0.1 * (r + 1), 1.0 / (r + 3), -1e-17 * r}; };
  const std::vector<double> sum = la::sum_over_processes(share(rank));
  std::vector<double> expected = share(0);
  for (int r = 1; r < size; ++r)
    for (std::size_t i = 0; i < expected.size(); ++i) expected[i] += share(r)[i];
  EXPECT_EQ(sum, expected);
  const std::vector<double> everyone = la::all_gather(sum);
  for (std::size_t i = 0; i < everyone.size(); ++i) EXPECT_EQ(everyone[i], sum[i % sum.size()]);
}

// A checkpoint's matrix (run/checkpoint.hpp) does not depend on the number of
// processes: the replicated copy of the distributed matrix is the serial
// pattern and matrix bit for bit, and a matrix made from it is the same.
TEST_P(Distributed2D3D, ReplicatedCopyIsTheSerialMatrixAndMakesItAgain) {
  const auto m = setup::build_discretization(config());
  const auto d = distribute(m);
  const auto K = system::assemble_stiffness(m, d);
  const la::Matrix::Replicated r = K.K.replicated();
  const assembly::SparsityPattern serial_pattern = assembly::build_sparsity(m.dofmap, &m.nonlocal->graph);
  EXPECT_EQ(r.pattern.block_size, serial_pattern.block_size);
  EXPECT_EQ(r.pattern.row_offsets, serial_pattern.row_offsets);
  EXPECT_EQ(r.pattern.columns, serial_pattern.columns);
  const Eigen::MatrixXd serial = serial_stiffness(m);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(serial.rows(), serial.cols());
  const Index bs = r.pattern.block_size;
  std::size_t at = 0;
  for (Index b = 0; b < r.pattern.num_block_rows(); ++b)
    for (Index i = 0; i < bs; ++i)
      for (Index c : r.pattern.row(b))
        for (Index j = 0; j < bs; ++j) dense(b * bs + i, c * bs + j) = r.values[at++];
  ASSERT_EQ(at, r.values.size());
  EXPECT_TRUE((serial.array() == dense.array()).all())
      << "bit for bit; max difference " << (serial - dense).cwiseAbs().maxCoeff();
  const la::Matrix again = la::Matrix::from_replicated(r, d);
  EXPECT_TRUE((again.to_dense().array() == serial.array()).all());
  const la::Matrix::Replicated r2 = again.replicated();
  EXPECT_EQ(r2.pattern.columns, r.pattern.columns);
  EXPECT_TRUE(r2.values == r.values);
}

TEST_P(Distributed2D3D, DiagonalAndBlocksAreTheSerialOnesOnEveryProcess) {
  const auto m = setup::build_discretization(config());
  const auto K = system::assemble_stiffness(m, distribute(m));
  const Eigen::MatrixXd serial = serial_stiffness(m);
  const Index n = m.dofmap.num_dofs();
  // Rows spread over every part, repeated, in no order.
  const std::vector<Index> rows{n - 1, 0, n / 2, 1, n / 3, 0};
  const std::vector<double> diag = K.K.diagonal_at(rows);
  for (std::size_t k = 0; k < rows.size(); ++k) EXPECT_EQ(diag[k], serial(rows[k], rows[k]));
  // The blocks of a few cells (as cell_mechanisms takes them), one gathering.
  std::vector<std::vector<Index>> sets;
  for (Index c : {Index{0}, m.mesh.num_cells() / 2, m.mesh.num_cells() - 1}) {
    auto& dofs = sets.emplace_back();
    for (Index node : m.dofmap.cell_nodes(c))
      for (int k = 0; k < m.dim(); ++k) dofs.push_back(node * m.dim() + k);
  }
  const std::vector<Eigen::MatrixXd> blocks = K.K.blocks(sets);
  ASSERT_EQ(blocks.size(), sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s)
    for (std::size_t i = 0; i < sets[s].size(); ++i)
      for (std::size_t j = 0; j < sets[s].size(); ++j)
        EXPECT_EQ(blocks[s](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)),
                  serial(sets[s][i], sets[s][j]));
  EXPECT_TRUE((K.K.block(sets[1]).array() == blocks[1].array()).all());
}

TEST_P(Distributed2D3D, BondsOverAThresholdAreDecidedOnceAndGatheredInTheSerialOrder) {
  casefile::CaseConfig c = config();
  c.fracture.enabled = true;
  c.fracture.s_crit = 1e-3;
  const auto m = setup::build_discretization(c);
  // A displacement with stretches of every size: u = x² along x (and a shear).
  std::vector<double> u(static_cast<std::size_t>(m.dofmap.num_dofs()), 0.0);
  for (Index node = 0; node < m.dofmap.num_nodes(); ++node) {
    const Vec3 x = m.dofmap.node_coordinate(m.mesh, node);
    u[static_cast<std::size_t>(node * m.dim())] = 1e-3 * x.x() * x.x();
    u[static_cast<std::size_t>(node * m.dim() + 1)] = 1e-4 * x.x() * x.y();
  }
  const auto space = m.nonlocal_space();
  const double threshold = c.fracture.s_crit;
  const auto serial = assembly::bonds_over(space, u, threshold);
  ASSERT_GT(serial.size(), 10u);
  const auto p = partition::coordinate_bisection(m.mesh, la::world_size());
  std::vector<char> mine(p.owner.size());
  for (std::size_t cell = 0; cell < mine.size(); ++cell)
    mine[cell] = p.owner[cell] == la::world_rank() ? 1 : 0;
  const auto decided = assembly::bonds_over(space, u, threshold, mine);
  // Every bond is decided by exactly one process.
  double total = 0.0;
  for (double n : la::all_gather({static_cast<double>(decided.size())})) total += n;
  EXPECT_EQ(total, static_cast<double>(serial.size()));
  // BondFailure's selection on a part is the process's decided bonds, in the
  // serial order.
  evolution::RunState state(m);
  state.u = u;
  const auto selected = evolution::BondFailure(m).select(state);
  ASSERT_EQ(selected.size(), decided.size());
  for (std::size_t k = 0; k < decided.size(); ++k) {
    const auto &a = selected[k].id, &b = decided[k].id;
    EXPECT_TRUE(a.e == b.e && a.f == b.f && a.g == b.g && a.h == b.h) << "bond " << k;
    EXPECT_EQ(selected[k].stretch, decided[k].stretch);
    EXPECT_EQ(selected[k].k, decided[k].k);
  }
}

// Floating parts (evolution/floating_parts.hpp) from the links each process
// finds in its part's cells, gathered: the serial parts and pins on every
// process. A fully non-local (DG) plate, held at x = 0 and along x at x = 4,
// with every bond across x = 2 failed: its right half is free along y.
TEST(DistributedFloatingParts, GatheredLinksGiveTheSerialPartsAndPins) {
  auto c = testing::box_case(2, {16, 8, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::gaussian, 0.375, 0.125, 2,
                        casefile::Discretization::discontinuous);
  c.alpha.value = 1.0;
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  c.dirichlet = {testing::fixed("xmin", 0), testing::fixed("xmin", 1), testing::fixed("xmax", 0, 0.004)};
  const auto m = setup::build_discretization(c);
  const auto& pts = m.nonlocal->points;
  const std::vector<double> zero(static_cast<std::size_t>(m.dofmap.num_dofs()), 0.0);
  bonds::BrokenBonds broken(m.mesh.num_cells(), pts.per_cell);
  for (const auto& b :
       assembly::bonds_over(m.nonlocal_space(), zero, -std::numeric_limits<double>::infinity()))
    if ((pts.x[pts.index(b.id.e, b.id.g)].x() < 2.0) != (pts.x[pts.index(b.id.f, b.id.h)].x() < 2.0))
      broken.add(b.id);
  ASSERT_GT(broken.size(), 50u);
  const auto space = m.nonlocal_space(&broken);
  const std::vector<Index> held = setup::build_dirichlet(m).dofs;
  const auto whole_links = evolution::stiffness_links(m, space);
  const auto serial = evolution::find_floating_parts(m, whole_links, held, {});
  ASSERT_EQ(serial.parts, 1);
  const auto gathered = evolution::stiffness_links_over_processes(m, space);
  if (la::world_size() > 1) {
    EXPECT_NE(gathered, whole_links) << "the links were not found per process";
  }
  const auto distributed = evolution::find_floating_parts(m, gathered, held, {});
  EXPECT_EQ(distributed.parts, serial.parts);
  EXPECT_EQ(distributed.pins, serial.pins);
}

// What process 0 alone does (the output) ends the same way on every process.
TEST(OnProcessZero, AnErrorOfProcessZeroStopsEveryProcess) {
  int calls = 0;
  la::on_process_zero([&] { ++calls; });
  EXPECT_EQ(calls, la::world_rank() == 0 ? 1 : 0);
  auto fail = [] { throw OutputError("disk full"); };
  if (la::world_rank() == 0) {
    EXPECT_THROW(la::on_process_zero(fail), OutputError);
  } else {
    try {
      la::on_process_zero(fail);
      ADD_FAILURE() << "no exception on process " << la::world_rank();
    } catch (const StoppedByProcessZero& e) {
      EXPECT_TRUE(e.output);
    }
  }
  if (la::world_rank() != 0) {
    try {
      la::on_process_zero([] { throw std::runtime_error("other"); });
      ADD_FAILURE() << "no exception on process " << la::world_rank();
    } catch (const StoppedByProcessZero& e) {
      EXPECT_FALSE(e.output);
    }
  } else {
    EXPECT_THROW(la::on_process_zero([] { throw std::runtime_error("other"); }), std::runtime_error);
  }
}

// Every process's share of the output (its VTU piece): an error on any
// process reaches the user once, from process 0, naming the process.
TEST(OnEveryProcess, TheLowestFailingProcessIsReportedByProcessZero) {
  const int rank = la::world_rank(), size = la::world_size();
  int calls = 0;
  la::on_every_process([&] { ++calls; });
  EXPECT_EQ(calls, 1);
  // Only the last process fails.
  auto last_fails = [&] {
    if (rank == size - 1) throw OutputError("disk full");
  };
  if (rank == 0) {
    try {
      la::on_every_process(last_fails);
      ADD_FAILURE() << "no exception on process 0";
    } catch (const StoppedByProcessZero&) {
      ADD_FAILURE() << "process 0 must report, not be stopped";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()),
                size == 1 ? "disk full" : fmt::format("process {}: disk full", size - 1));
    }
  } else {
    try {
      la::on_every_process(last_fails);
      ADD_FAILURE() << "no exception on process " << rank;
    } catch (const StoppedByProcessZero& e) {
      EXPECT_TRUE(e.output);
    }
  }
  // Every process but 0 fails, each its own way: process 1's error is reported.
  auto others_fail = [&] {
    if (rank > 0) throw std::runtime_error(fmt::format("on {}", rank));
  };
  if (size == 1) {
    EXPECT_NO_THROW(la::on_every_process(others_fail));
  } else if (rank == 0) {
    try {
      la::on_every_process(others_fail);
      ADD_FAILURE() << "no exception on process 0";
    } catch (const OutputError&) {
      ADD_FAILURE() << "not an output error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "process 1: on 1");
    }
  } else {
    try {
      la::on_every_process(others_fail);
      ADD_FAILURE() << "no exception on process " << rank;
    } catch (const StoppedByProcessZero& e) {
      EXPECT_FALSE(e.output);
    }
  }
}

}  // namespace
}  // namespace perimorph

namespace {

/// On several processes, a fatal failure (an ASSERT_*, or an exception out of
/// a test) on one process returns from its test while the others go on to the
/// next collective call and wait there until ctest's timeout: every process
/// is stopped at once instead, after the failure has been printed.
class StopEveryProcessOnAFatalFailure final : public ::testing::EmptyTestEventListener {
 public:
  void OnTestPartResult(const ::testing::TestPartResult& result) override {
    if (!result.fatally_failed() || perimorph::la::world_size() == 1) return;
    std::fprintf(stderr, "process %d: a fatal failure; stopping every process (%s:%d)\n",
                 perimorph::la::world_rank(), result.file_name() ? result.file_name() : "?",
                 result.line_number());
    perimorph::la::abort_every_process(1);
  }
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  perimorph::la::PetscSession petsc(argc, argv);
  // After gtest's printer, which reports the failure first.
  ::testing::UnitTest::GetInstance()->listeners().Append(new StopEveryProcessOnAFatalFailure);
  return RUN_ALL_TESTS();
}
