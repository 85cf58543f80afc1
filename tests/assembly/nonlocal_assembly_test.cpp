// The structural optimizations of the non-local assembly (issue 3, item 9)
// change the cost, not the matrix: the plain version (points recomputed per
// pair) equals the precomputed one bit for bit; the α ≡ 1 shortcut and the
// translation cache agree to round-off. Checked with the plain cut-off and
// with partial-volume bonds, on a hybrid 3D block with a pre-crack cut; the
// bond count `perimorph info` prints is the count the stiffness sums.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace perimorph {
namespace {

Eigen::MatrixXd assemble(const setup::Discretization& m, const assembly::NonlocalOptions& options,
                         assembly::NonlocalStats* stats = nullptr) {
  const auto& nl = *m.nonlocal;
  testing::DenseInserter K(m.dofmap.num_dofs());
  assembly::NonlocalSpace space{m.mesh, m.dofmap, nl.points, nl.graph, nl.kernel, &nl.alpha, m.scale};
  const auto s = assembly::assemble_nonlocal(space, K, options);
  if (stats) *stats = s;
  return K.A;
}

/// A hybrid 3D block with a pre-crack cut: α ≡ 1 on the 8 cells about
/// (1.0, 0.5, 0.25), whose pairs go through the translation cache; the cut
/// (plane x = 0.125, y < 0.5) is far enough from them.
setup::Discretization cut_block(casefile::HorizonEdge edge) {
  auto c = testing::box_case(3, {10, 8, 4}, Vec3(1.25, 1.0, 0.5), 90.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::exponential, 0.3, 0.06, 2);
  c.nonlocal.horizon_edge = edge;
  c.alpha.regions = {testing::alpha_ball(Vec3(1.0, 0.5, 0.25), 0.25, 0.15)};
  casefile::CutSpec cut;
  cut.origin = Vec3(0.125, 0.0, 0.0);
  cut.edge1 = Vec3(0.0, 0.5, 0.0);
  cut.edge2 = Vec3(0.0, 0.0, 0.5);
  c.mesh.cuts = {cut};
  return setup::build_discretization(c);
}

TEST(AssemblyNonlocal, OptimizationsDoNotChangeTheMatrix) {
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume}) {
    SCOPED_TRACE(edge == casefile::HorizonEdge::cutoff ? "cutoff" : "partial volume");
    const auto m = cut_block(edge);
    assembly::NonlocalOptions plain{false, false, false, {}}, points{true, false, false, {}}, all{};
    const Eigen::MatrixXd A = assemble(m, plain), B = assemble(m, points);
    assembly::NonlocalStats stats;
    const Eigen::MatrixXd C = assemble(m, all, &stats);
    ASSERT_EQ(A.size(), B.size());
    EXPECT_EQ(std::memcmp(A.data(), B.data(), sizeof(double) * static_cast<std::size_t>(A.size())), 0);
    const double scale = A.cwiseAbs().maxCoeff();
    EXPECT_GT(scale, 0.0);
    EXPECT_LT((A - C).cwiseAbs().maxCoeff(), 1e-13 * scale);
    EXPECT_GT(stats.reused_pairs, 0u) << "the cache was not exercised";
  }
}

// The bond count of `perimorph info` (assembly::count_bonds) is the count of
// the bonds the non-local stiffness sums, with either edge rule, and differs
// from the count of interacting cell pairs.
TEST(AssemblyNonlocal, BondCountIsWhatTheStiffnessSums) {
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume}) {
    SCOPED_TRACE(edge == casefile::HorizonEdge::cutoff ? "cutoff" : "partial volume");
    const auto m = cut_block(edge);
    const auto& nl = *m.nonlocal;
    const assembly::NonlocalSpace space{m.mesh, m.dofmap, nl.points, nl.graph, nl.kernel, &nl.alpha, m.scale};
    assembly::NonlocalStats stats;
    assemble(m, {false, false, false, {}}, &stats);
    const auto count = assembly::count_bonds(space);
    EXPECT_GT(count.bonds, 0u);
    EXPECT_EQ(count.bonds, stats.bonds);
    EXPECT_EQ(count.cell_pairs, stats.cell_pairs);
    EXPECT_GT(count.bonds, nl.graph.num_pairs());
  }
}

TEST(AssemblyNonlocal, PartialVolumeAddsEdgeBondsOnly) {
  // Partial volumes keep every interior bond as it is, weigh the bonds near
  // |ξ| = δ and add bonds slightly beyond δ: more bonds, a matrix that differs
  // only a little (the edge is a thin shell of the horizon).
  auto c = testing::box_case(2, {12, 12, 1}, Vec3(1.0, 1.0, 0), 1.0, 0.25);
  testing::add_nonlocal(c, casefile::KernelKind::constant, 0.25, 0.0, 3);
  c.alpha.value = 1.0;
  const auto cut = setup::build_discretization(c);
  c.nonlocal.horizon_edge = casefile::HorizonEdge::partial_volume;
  const auto pv = setup::build_discretization(c);
  assembly::NonlocalStats s_cut, s_pv;
  const Eigen::MatrixXd A = assemble(cut, {}, &s_cut), B = assemble(pv, {}, &s_pv);
  std::printf("bonds: cut-off %zu, partial volume %zu; max|K_pv − K_cut|/max|K| = %.3e\n", s_cut.bonds,
              s_pv.bonds, (B - A).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff());
  EXPECT_GT(s_pv.bonds, s_cut.bonds);
  EXPECT_GT((B - A).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((B - A).cwiseAbs().maxCoeff(), 0.2 * A.cwiseAbs().maxCoeff());
  EXPECT_LT((B - B.transpose()).cwiseAbs().maxCoeff(), 1e-14 * B.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace perimorph
