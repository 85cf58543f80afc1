#pragma once
// The links of the stiffness graph that the search for floating parts needs
// (floating_parts.hpp), found on the pieces of a distributed run without
// gathering the whole graph on every process (issue 17, item 2).
//
// A part held in every rigid-body direction gets no pins and adds nothing to
// the search: only the parts the held dofs may leave free need their links
// whole, and those are the fragments a crack cuts loose, not the body. Each
// process finds the parts of its own cells' links; each node goes to one
// process (la::hashed_process of its key), which joins the processes' parts
// meeting at the node and counts the node once for its part's figures (node
// count, centre, size, and the Gram matrix of its held dofs' rigid-body rows);
// the parts whose held rows may not span every mode are then gathered whole.

#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>
#include <vector>

namespace perimorph::evolution {

/// The links (stiffness_links: flat pairs node, root) of the parts of the
/// whole stiffness graph that `held` (dof names, sorted) might not hold in
/// every rigid-body direction, on every process, and in `positions` the
/// position of each link's first node: find_floating_parts given them finds
/// the same floating parts, pins and figures, and throws the same error, as
/// given every link. On one process or on parts of the whole model, every
/// link (stiffness_links_over_processes). On pieces (collective): the nodes
/// named by their keys; each process sends the nodes its cells' links reach
/// to the process counting each (40 bytes a node), and receives whole only
/// the links of the parts that may float. A part counts as possibly free when
/// it has no held dof or when the smallest eigenvalue of Σ r̂ r̂ᵀ over its held
/// dofs' rigid_mode_rows r̂ (normalized; centre and size summed over the
/// processes) is at most 1e-10 per row: a part find_floating_parts finds free
/// has one below 1e-16 per row (kHeldSpanTolerance squared), so no floating
/// part is left out whatever the round-off of the sums.
std::vector<Index> links_of_loosely_held_parts(const setup::Discretization& disc,
                                               const assembly::NonlocalSpace& space,
                                               std::span<const Index> held, std::vector<Vec3>* positions);

}  // namespace perimorph::evolution
