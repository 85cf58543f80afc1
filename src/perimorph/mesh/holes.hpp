#pragma once
// Holes in a mesh: remove cells (a stair-stepped hole when they are the cells
// whose centroid lies in a shape), drop the nodes no cell uses any more and
// renumber what remains.

#include "perimorph/core/hole.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <vector>

namespace perimorph::mesh {

/// Removes every cell c with remove[c] != 0 (remove has one entry per cell),
/// then every node that no remaining cell uses. Remaining cells and nodes keep
/// their order and are numbered 0, 1, ... again. Node, face and cell sets lose
/// the removed entries and are renumbered (a set may become empty; it is
/// kept), cell_region follows its cells, cuts are kept. The structured layout
/// is dropped (cell indices no longer follow the grid). The faces uncovered by
/// the removal join no face or node set ("boundary" included).
void remove_cells(Mesh& mesh, const std::vector<char>& remove);

/// Removes the cells whose centroid lies strictly inside `hole` (see
/// remove_cells) and returns their number. Throws InputError, naming the
/// shape, if the hole removes no cell or every cell.
Index remove_hole(Mesh& mesh, const Hole& hole);

}  // namespace perimorph::mesh
