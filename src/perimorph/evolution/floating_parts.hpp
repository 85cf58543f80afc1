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
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/setup/discretization.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace perimorph::evolution {

/// The rigid-body modes of a body in `dim` dimensions: 1, 3 or 6.
constexpr int rigid_modes(int dim) {
  return dim == 1 ? 1 : dim == 2 ? 3 : 6;
}

/// The value of each rigid-body mode at component d of a node at p (relative
/// to the part's centre, in units of its size): translations, then rotations.
Eigen::VectorXd rigid_mode_row(int dim, const Vec3& p, int d);

/// A part is held when its held dofs' rigid_mode_rows span every mode: each
/// row, in the order of the nodes' names, adds the part of it outside the
/// span of those before when that is over this fraction of the row
/// (modified Gram–Schmidt).
inline constexpr double kHeldSpanTolerance = 1e-8;

struct FloatingParts {
  int parts = 0;            ///< parts with at least one free rigid-body mode
  std::vector<Index> pins;  ///< dofs that, held, remove those modes (sorted)
};

/// The links of the stiffness graph (nodes joined by a cell's local stiffness
/// or by an intact bond between two cells, either of which couples every node
/// of the cells involved) seen from the flagged cells (`cells`, one flag per
/// cell; all if empty): the cells with a local stiffness among them and the
/// cell pairs {e, f}, e ≤ f, joined by an intact bond with e flagged. As flat
/// pairs (node, root), one per node they reach, root the smallest node it is
/// joined to through them (itself if none). The links of the parts of a
/// partition, together, join the nodes as the whole graph's do: a process
/// finds the links of its part's cells, reading their graph rows only, and the
/// processes' links are gathered (issue 17).
std::vector<Index> stiffness_links(const setup::Discretization& model, const assembly::NonlocalSpace& space,
                                   std::span<const char> cells = {});

/// The links of the whole stiffness graph, on every process: on several, each
/// finds those of its part's cells (setup::cells_of_process, the cells of the
/// stretch pass: their graph rows only) and they are gathered (collective;
/// 16 bytes a node a part reaches). On one, stiffness_links of every cell. On
/// a piece of the model (setup::cut_to_piece) the nodes are named by their
/// keys (partition::PieceDofs; setup::dof_name names their dofs), and
/// `positions` gets the position of each link's first node (40 bytes a node);
/// a run on pieces gathers only the links find_floating_parts needs
/// (links_of_loosely_held_parts, floating_part_links.hpp).
std::vector<Index> stiffness_links_over_processes(const setup::Discretization& model,
                                                  const assembly::NonlocalSpace& space,
                                                  std::vector<Vec3>* positions = nullptr);

/// The parts of the stiffness graph made by `links` (stiffness_links; nodes
/// reached by no link have no stiffness at all and are left out: BondFailure
/// holds those one by one) and their free rigid-body modes, given the dofs
/// already held (`held`: prescribed or pinned before, sorted). `force`: the
/// applied forces at load factor 1 (empty: none), read at the floating parts'
/// dofs only, once (collective where they are spread: every process passes the
/// same links and held dofs). Throws Error naming the part when the forces do
/// work on one of its free modes. The same parts, pins and figures for any
/// split of the links, in any order. The links may name nodes otherwise than
/// `model` numbers them (a piece's: stiffness_links_over_processes), with
/// `positions` then the position of each link's first node, and `held`,
/// `force`'s dofs and the pins named alike (node name × dim + component), in
/// whichever order the names sort the nodes.
FloatingParts find_floating_parts(const setup::Discretization& model, std::span<const Index> links,
                                  std::span<const Index> held, const la::DofValuesAt& force,
                                  std::span<const Vec3> positions = {});

}  // namespace perimorph::evolution
