#include "perimorph/partition/piece_dofs.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/part_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace perimorph::partition {

Index PieceDofs::num_owned() const {
  return static_cast<Index>(std::count(owned.begin(), owned.end(), 1));
}

PieceDofs piece_dofs(const dofs::DofMap& local, const mesh::PartMesh& piece, std::span<const int> cell_owner,
                     int part, Index whole_nodes, Index whole_cells) {
  const Index cells = local.num_cells();
  if (cells != piece.mesh.num_cells() || static_cast<Index>(cell_owner.size()) != cells)
    throw Error(fmt::format("piece dofs: the dof map has {} cells, the piece {}, the owners {}", cells,
                            piece.mesh.num_cells(), cell_owner.size()));
  const int k = piece.mesh.nodes_per_cell();
  const long long space = static_cast<long long>(whole_nodes) + static_cast<long long>(whole_cells) * k;
  if (space > std::numeric_limits<Index>::max())
    throw Error(
        fmt::format("piece dofs: {} nodes and {} cells need keys up to {}, beyond PETSc's 32-bit "
                    "indices; a PETSc built with 64-bit indices would be needed",
                    whole_nodes, whole_cells, space));
  PieceDofs out;
  out.key_space = static_cast<Index>(space);
  const auto nodes = static_cast<std::size_t>(local.num_nodes());
  out.key.assign(nodes, -1);
  std::vector<int> owner(nodes, std::numeric_limits<int>::max());
  for (Index c = 0; c < cells; ++c) {
    const auto cell_nodes = local.cell_nodes(c);
    const auto mesh_nodes = piece.mesh.cell(c);
    const Index g = piece.global_cell[static_cast<std::size_t>(c)];
    for (std::size_t a = 0; a < cell_nodes.size(); ++a) {
      const auto n = static_cast<std::size_t>(cell_nodes[a]);
      out.key[n] = local.continuity(c) == dofs::Continuity::continuous
                       ? piece.global_node[static_cast<std::size_t>(mesh_nodes[a])]
                       : whole_nodes + g * k + static_cast<Index>(a);
      owner[n] = std::min(owner[n], cell_owner[static_cast<std::size_t>(c)]);
    }
  }
  out.owned.assign(nodes, 0);
  for (std::size_t n = 0; n < nodes; ++n) {
    PERIMORPH_ASSERT(out.key[n] >= 0, "piece dofs: a dof node of no cell");
    PERIMORPH_ASSERT(n == 0 || out.key[n - 1] < out.key[n],
                     "piece dofs: the piece's dof nodes are not in the whole model's order");
    out.owned[n] = owner[n] == part ? 1 : 0;
  }
  return out;
}

}  // namespace perimorph::partition
