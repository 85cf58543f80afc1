// The bond count of `perimorph info` (assembly::count_bonds) is the count of
// the bonds the non-local stiffness sums (NonlocalStats of the assembly), with
// the cut-off and with partial volumes, on a hybrid 3D block with a pre-crack
// cut, and it differs from the count of interacting cell pairs.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/driver/model.hpp"
#include "support/cases.hpp"
#include "support/dense_inserter.hpp"

#include <gtest/gtest.h>

namespace perimorph {
namespace {

TEST(AssemblyBondCount, CountsTheBondsTheStiffnessSums) {
  for (auto edge : {casefile::HorizonEdge::cutoff, casefile::HorizonEdge::partial_volume}) {
    SCOPED_TRACE(edge == casefile::HorizonEdge::cutoff ? "cutoff" : "partial volume");
    auto c = testing::box_case(3, {10, 8, 4}, Vec3(1.25, 1.0, 0.5), 90.0, 0.25);
    testing::add_nonlocal(c, casefile::KernelKind::exponential, 0.3, 0.06, 2);
    c.nonlocal.horizon_edge = edge;
    c.alpha.regions = {testing::alpha_ball(Vec3(1.0, 0.5, 0.25), 0.25, 0.15)};
    casefile::CutSpec cut;
    cut.origin = Vec3(0.125, 0.0, 0.0);
    cut.edge1 = Vec3(0.0, 0.5, 0.0);
    cut.edge2 = Vec3(0.0, 0.0, 0.5);
    c.mesh.cuts = {cut};
    const auto m = driver::build_model(c);
    const auto& nl = *m.nonlocal;
    const assembly::NonlocalSpace space{m.mesh, m.dofmap, nl.points, nl.graph, nl.kernel, &nl.alpha, m.scale};
    testing::DenseInserter K(m.dofmap.num_dofs());
    const auto stats = assembly::assemble_nonlocal(space, K, {false, false, false});
    const auto count = assembly::count_bonds(space);
    EXPECT_GT(count.bonds, 0u);
    EXPECT_EQ(count.bonds, stats.bonds);
    EXPECT_EQ(count.cell_pairs, stats.cell_pairs);
    EXPECT_GT(count.bonds, nl.graph.num_pairs());
  }
}

}  // namespace
}  // namespace perimorph
