#include "perimorph/dofs/dof_map.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <algorithm>

namespace perimorph::dofs {

DofMap::DofMap(const mesh::Mesh& mesh, int block_size, std::span<const Continuity> continuity)
    : block_size_(block_size) {
  const Index ncells = mesh.num_cells();
  PERIMORPH_ASSERT(continuity.empty() || static_cast<Index>(continuity.size()) == ncells,
                   "continuity flags must be given for every cell");
  continuity_.assign(static_cast<std::size_t>(ncells), Continuity::continuous);
  if (!continuity.empty()) std::copy(continuity.begin(), continuity.end(), continuity_.begin());

  // CG dof nodes: mesh nodes touched by a continuous cell, in mesh order.
  std::vector<Index> cg_node(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (Index c = 0; c < ncells; ++c)
    if (continuity_[static_cast<std::size_t>(c)] == Continuity::continuous)
      for (Index n : mesh.cell(c)) cg_node[static_cast<std::size_t>(n)] = 0;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (cg_node[static_cast<std::size_t>(n)] == 0) {
      cg_node[static_cast<std::size_t>(n)] = static_cast<Index>(mesh_node_.size());
      mesh_node_.push_back(n);
    }

  offsets_.reserve(static_cast<std::size_t>(ncells) + 1);
  offsets_.push_back(0);
  cell_nodes_.reserve(mesh.connectivity().size());
  for (Index c = 0; c < ncells; ++c) {
    if (continuity_[static_cast<std::size_t>(c)] == Continuity::discontinuous_constant) {
      cell_nodes_.push_back(static_cast<Index>(mesh_node_.size()));
      mesh_node_.push_back(-2 - c);
      offsets_.push_back(static_cast<Index>(cell_nodes_.size()));
      continue;
    }
    for (Index n : mesh.cell(c)) {
      if (continuity_[static_cast<std::size_t>(c)] == Continuity::continuous) {
        cell_nodes_.push_back(cg_node[static_cast<std::size_t>(n)]);
      } else {
        cell_nodes_.push_back(static_cast<Index>(mesh_node_.size()));
        mesh_node_.push_back(n);
      }
    }
    offsets_.push_back(static_cast<Index>(cell_nodes_.size()));
  }
}

Vec3 DofMap::node_coordinate(const mesh::Mesh& mesh, Index n) const {
  const Index m = stored_mesh_node(n);
  return m >= 0 ? mesh.node(m) : mesh.cell_centroid(-2 - m);
}

std::vector<Vec3> DofMap::node_coordinates(const mesh::Mesh& mesh) const {
  std::vector<Vec3> out;
  out.reserve(mesh_node_.size());
  for (Index n = 0; n < num_nodes(); ++n) out.push_back(node_coordinate(mesh, n));
  return out;
}

std::vector<Index> DofMap::dof_nodes_of_mesh_nodes(std::span<const Index> mesh_nodes) const {
  Index max_node = 0;
  for (Index m : mesh_node_) max_node = std::max(max_node, m);
  std::vector<char> wanted(static_cast<std::size_t>(max_node) + 1, 0);
  for (Index m : mesh_nodes)
    if (m <= max_node) wanted[static_cast<std::size_t>(m)] = 1;
  std::vector<Index> out;
  for (Index n = 0; n < num_nodes(); ++n) {
    const Index m = mesh_node_[static_cast<std::size_t>(n)];
    if (m >= 0 && wanted[static_cast<std::size_t>(m)]) out.push_back(n);
  }
  return out;
}

std::vector<Index> DofMap::dof_nodes_of_cells(std::span<const Index> cells) const {
  std::vector<Index> out;
  for (Index c : cells)
    for (Index n : cell_nodes(c)) out.push_back(n);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace perimorph::dofs
