#pragma once
// Parts cut free by bond failure (THEORY §5). Failures can split the body
// into pieces that no support holds in every rigid-body direction (a
// fragment, or the half of a specimen held only along the loading axis); the
// stiffness matrix is then singular. This finds the connected parts of the
// stiffness graph and, for each part whose prescribed dofs leave rigid-body
// modes free, chooses a minimal set of extra dofs that removes them: a
// statically determinate support, so it carries no force when the loads on
// the part are self-equilibrated. A part whose applied forces do work on a
// free mode has no quasi-static equilibrium; that is an error.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>
#include <vector>

namespace perimorph::evolution {

struct FloatingParts {
  int parts = 0;            ///< parts with at least one free rigid-body mode
  std::vector<Index> pins;  ///< dofs that, held, remove those modes (sorted)
};

/// The parts of the stiffness graph (nodes joined by a cell's local stiffness
/// or by an intact bond between two cells, either of which couples every node
/// of the cells involved) and their free rigid-body modes, given the dofs
/// already held (`held`: prescribed or pinned before, sorted). Nodes with no
/// stiffness at all are left out (BondFailure holds those one by one).
/// `force`: the applied forces at load factor 1 (empty: none). Throws Error
/// naming the part when the forces do work on one of its free modes.
FloatingParts find_floating_parts(const setup::Discretization& model, const assembly::NonlocalSpace& space,
                                  std::span<const Index> held, std::span<const double> force);

}  // namespace perimorph::evolution
