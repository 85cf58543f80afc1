#pragma once
// The degree-of-freedom map as plain data (STYLE.md habit 5, DOLFINx-like):
// per cell a span of dof nodes, each carrying block_size components, with a
// per-cell continuity flag. Continuous (CG) cells share the mesh's vertex
// nodes; discontinuous (DG) cells own private copies of their vertices, so the
// displacement may jump across their faces (THEORY §4). Dof numbering is
// interleaved: dof = node * block_size + component.
//
// Parallel readiness: owned dof nodes are [0, num_owned); ghosts follow (none
// in a serial run). Global numbers are the local ones offset by owned_offset.

#include "perimorph/core/types.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}

namespace perimorph::dofs {

/// continuous: shares the mesh's vertex nodes (CG); discontinuous: private
/// copies of its vertices (DG, degree 1); discontinuous_constant: one private
/// node at the centroid with a constant shape function (DG degree 0, the
/// meshfree discretization, THEORY §4).
enum class Continuity : std::uint8_t { continuous = 0, discontinuous = 1, discontinuous_constant = 2 };

class DofMap {
 public:
  /// CG on every cell whose flag is continuous, DG on the others. An empty
  /// span means CG everywhere.
  DofMap(const mesh::Mesh& mesh, int block_size, std::span<const Continuity> continuity = {});

  int block_size() const { return block_size_; }
  Index num_nodes() const { return static_cast<Index>(mesh_node_.size()); }
  Index num_dofs() const { return num_nodes() * block_size_; }
  Index num_owned_nodes() const { return num_nodes(); }
  Index owned_offset() const { return 0; }

  std::span<const Index> cell_nodes(Index c) const {
    assert(c >= 0 && c < num_cells());
    return {cell_nodes_.data() + offsets_[static_cast<std::size_t>(c)],
            static_cast<std::size_t>(offsets_[static_cast<std::size_t>(c) + 1] -
                                     offsets_[static_cast<std::size_t>(c)])};
  }
  Index num_cells() const { return static_cast<Index>(offsets_.size()) - 1; }
  Continuity continuity(Index c) const {
    assert(c >= 0 && static_cast<std::size_t>(c) < continuity_.size());
    return continuity_[static_cast<std::size_t>(c)];
  }
  /// Where dof node n sits: the vertex of `mesh` it copies, or for DG degree
  /// 0 its cell's centroid. `mesh` is the one the map was built from; the map
  /// keeps no copy of the coordinates (24 bytes a dof node).
  Vec3 node_coordinate(const mesh::Mesh& mesh, Index n) const;
  /// Every dof node's coordinate, in order (a whole-length array, built on
  /// each call: for a report or a test, not for a distributed run's loop).
  std::vector<Vec3> node_coordinates(const mesh::Mesh& mesh) const;
  /// node_coordinate on `mesh` as a function of the node (the solver's
  /// la::NodeCoordinate); it refers to this map and `mesh`, which must outlive it.
  std::function<Vec3(Index)> node_coordinate_on(const mesh::Mesh& mesh) const {
    return [this, &mesh](Index n) { return node_coordinate(mesh, n); };
  }
  /// Mesh node this dof node copies (CG: itself; DG: the vertex it
  /// duplicates; DG degree 0: -1, the node is a cell centroid).
  Index mesh_node(Index n) const { return std::max<Index>(stored_mesh_node(n), -1); }
  /// The cell whose centroid dof node n is (DG degree 0), or -1.
  Index centroid_cell(Index n) const { return std::max<Index>(-stored_mesh_node(n) - 2, -1); }
  /// Dof nodes that copy the given mesh nodes (one for CG, one per DG cell touching it, ...).
  std::vector<Index> dof_nodes_of_mesh_nodes(std::span<const Index> mesh_nodes) const;
  /// Every dof node of the given cells, sorted and unique.
  std::vector<Index> dof_nodes_of_cells(std::span<const Index> cells) const;

 private:
  int block_size_;
  std::vector<Index> offsets_;
  std::vector<Index> cell_nodes_;
  std::vector<Continuity> continuity_;
  /// Per dof node, the mesh node it copies, or -2 - c for the centroid of
  /// DG degree 0 cell c.
  std::vector<Index> mesh_node_;

  Index stored_mesh_node(Index n) const {
    assert(n >= 0 && n < num_nodes());
    return mesh_node_[static_cast<std::size_t>(n)];
  }
};

}  // namespace perimorph::dofs
