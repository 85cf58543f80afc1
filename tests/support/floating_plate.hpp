#pragma once
// Test support for the supports of parts cut free (evolution/part_support.hpp):
// a fully non-local plate whose bonds across x = 2 are made to fail, its
// system, and one pass of the run's failure components. Used by
// tests/evolution/floating_parts_test.cpp and cell_mechanisms_test.cpp and,
// on a system spread over the processes, tests/mpi/system_mpitest.cpp.

#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace perimorph::testing {

/// Plate [0, 4] × [0, 2], fully non-local (DG), u_x = 0 on x = 0 and u_y = 0
/// at the origin; the right edge pulled to u_x = 0.004, or (traction) loaded
/// by a traction along x.
inline casefile::CaseConfig floating_plate(bool traction) {
  auto c = box_case(2, {16, 8, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
  add_nonlocal(c, casefile::KernelKind::gaussian, 0.375, 0.125, 2, casefile::Discretization::discontinuous);
  c.alpha.value = 1.0;
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  casefile::NodeSetSpec origin;
  origin.name = "origin";
  c.node_sets = {origin};
  c.dirichlet = {fixed("xmin", 0), fixed("origin", 1)};
  if (traction) {
    casefile::TractionSpec t;
    t.set = "xmax";
    t.value = Vec3(1e-3, 0.0, 0.0);
    c.tractions = {t};
  } else {
    c.dirichlet.push_back(fixed("xmax", 0, 0.004));
  }
  c.fracture.enabled = true;
  c.fracture.s_crit = 1e-6;
  return c;
}

/// floating_plate(false) with bonds that may fail only in a band around
/// x = 2, 1 wide (wider than the bonds), pulled in two increments (0.5, 1),
/// writing VTU and failed bonds at each: it is cut through there, its right
/// half held along x only (a floating part), cells of the band with motions
/// no bond resists. Run by tests/mpi/piece_fracture_mpitest.cpp and
/// piece_checkpoint_mpitest.cpp.
inline casefile::CaseConfig plate_cut_in_band() {
  auto plate = floating_plate(false);
  plate.loading.factors = {0.5, 1.0};
  casefile::RegionSpec left, right;
  left.name = "left";
  left.id = 1;
  left.upper = Vec3(1.5, 2.0, 1.0);
  right.name = "right";
  right.id = 2;
  right.lower = Vec3(2.5, 0.0, 0.0);
  right.upper = Vec3(4.0, 2.0, 1.0);
  plate.regions = {left, right};
  plate.fracture.no_fail = {"left", "right"};
  plate.output.vtu = true;
  plate.output.every = 1;
  plate.output.failed_bonds = true;
  return plate;
}

/// The run's constrained system of a model at load factor 1 (applied forces,
/// prescribed values), on one process.
inline system::ConstrainedSystem constrained_system(const setup::Discretization& model) {
  return system::ConstrainedSystem(model, system::assemble_stiffness(model).K, setup::build_dirichlet(model),
                                   setup::build_external_force(model));
}

/// Cells right of x = 2 moved by (1, 0): only the bonds across x = 2 stretch.
inline std::vector<double> jump_at_middle(const setup::Discretization& model) {
  const auto& dm = model.dofmap;
  std::vector<double> u(static_cast<std::size_t>(dm.num_dofs()), 0.0);
  for (Index c = 0; c < model.mesh.num_cells(); ++c) {
    const auto nodes = dm.cell_nodes(c);
    Vec3 centre = Vec3::Zero();
    for (Index a : nodes) centre += dm.node_coordinate(model.mesh, a);
    if (centre.x() / static_cast<double>(nodes.size()) > 2.0)
      for (Index a : nodes) u[static_cast<std::size_t>(a * 2)] = 1.0;
  }
  return u;
}

/// u_x = (x − 3.75)² on the nodes of the last column of cells (x > 3.75):
/// every bond there with a horizontal component stretches.
inline void stretch_last_column(const setup::Discretization& model, std::vector<double>& u) {
  for (Index cell = 0; cell < model.mesh.num_cells(); ++cell)
    if (model.mesh.cell_centroid(cell).x() > 3.75)
      for (Index a : model.dofmap.cell_nodes(cell)) {
        const double d = model.dofmap.node_coordinate(model.mesh, a).x() - 3.75;
        u[static_cast<std::size_t>(a * 2)] = d * d;
      }
}

/// One pass of the run's components at the state's displacement, as the run
/// loop makes it: bond failure inspects and applies, then the support of
/// parts cut free. Returns the number of bonds failed.
inline std::size_t break_and_support(const setup::Discretization& model, evolution::RunState& state,
                                     system::ConstrainedSystem& sys) {
  evolution::BondFailure failure(model);
  evolution::PartSupport support(model);
  const std::size_t bonds = failure.inspect(state, sys).changes;
  if (bonds > 0) {
    EXPECT_EQ(failure.apply(state, sys), evolution::Effect::downdate);
  }
  if (!support.inspect(state, sys).quiet()) {
    EXPECT_EQ(support.apply(state, sys), evolution::Effect::hold);
  }
  return bonds;
}

}  // namespace perimorph::testing
