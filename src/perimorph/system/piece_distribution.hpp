#pragma once
// The distribution of a piece's dof nodes (issue 17, item 1): the la::Distribution
// of a dof map built on a process's piece of the mesh (mesh::part_mesh), its
// to_distributed as long as the piece, from what the piece decides alone
// (partition::piece_dofs) plus two collective steps: the prefix sum of the
// owned counts places each process's range, and the ghosts' numbers come
// from their owners by key (la::values_of_keys). Nothing as long as the whole
// model is built or sent; the numbers are partition::dof_numbering's.

#include "perimorph/la/distribution.hpp"
#include "perimorph/partition/piece_dofs.hpp"

#include <memory>

namespace perimorph::system {

/// Collective over PETSC_COMM_WORLD: every process passes its piece's.
std::shared_ptr<const la::Distribution> piece_distribution(const partition::PieceDofs& piece);

}  // namespace perimorph::system
