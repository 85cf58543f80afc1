#pragma once
// A process's piece of a model for the tests of issue 17's halo numbering:
// the cells of one part of the coordinate bisection and every cell sharing a
// mesh node with one (cells_near_part), as a mesh of their own, with the dof
// map on it and what the piece decides about its dof nodes alone.

#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/mesh/part_mesh.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/partition/piece_dofs.hpp"

#include <span>
#include <vector>

namespace perimorph::testing {

/// CG, DG and DG degree 0 cells in diagonal stripes (from the centroid's
/// integer parts), so that every kind meets every other across the parts'
/// borders.
inline std::vector<dofs::Continuity> mixed_continuity(const mesh::Mesh& m) {
  std::vector<dofs::Continuity> out(static_cast<std::size_t>(m.num_cells()));
  for (Index c = 0; c < m.num_cells(); ++c) {
    const Vec3 x = m.cell_centroid(c);
    const int kind = (static_cast<int>(x[0]) + 2 * static_cast<int>(x[1])) % 5;
    out[static_cast<std::size_t>(c)] = kind < 2   ? dofs::Continuity::continuous
                                       : kind < 4 ? dofs::Continuity::discontinuous
                                                  : dofs::Continuity::discontinuous_constant;
  }
  return out;
}

struct TestPiece {
  mesh::PartMesh part;
  std::vector<int> owner;  ///< per local cell
  dofs::DofMap dofmap;     ///< on part.mesh, each cell's continuity the whole model's
  partition::PieceDofs dofs;
};

/// Part `part` of `p`'s piece of `whole`, with dof nodes of `block_size`.
inline TestPiece make_piece(const mesh::Mesh& whole, std::span<const dofs::Continuity> flags,
                            const partition::Partition& p, int part, int block_size) {
  std::vector<Index> cells;
  const auto near = partition::cells_near_part(whole, p.parts, part);
  for (Index c = 0; c < whole.num_cells(); ++c)
    if (near.empty() || near[static_cast<std::size_t>(c)]) cells.push_back(c);
  auto pm = mesh::part_mesh(whole, cells);
  std::vector<dofs::Continuity> local_flags;
  std::vector<int> owner;
  for (Index g : pm.global_cell) {
    local_flags.push_back(flags[static_cast<std::size_t>(g)]);
    owner.push_back(p.owner[static_cast<std::size_t>(g)]);
  }
  dofs::DofMap dm(pm.mesh, block_size, local_flags);
  auto d = partition::piece_dofs(dm, pm, owner, part, whole.num_nodes(), whole.num_cells());
  return {std::move(pm), std::move(owner), std::move(dm), std::move(d)};
}

}  // namespace perimorph::testing
