#pragma once
// One unstructured mesh type for bars, quads and hexes, with named node, face
// and element sets. Nodes always carry three coordinates (unused ones are 0),
// so geometry code is the same in every dimension.

#include "perimorph/core/cut.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/mesh/cell_type.hpp"

#include <array>
#include <cassert>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace perimorph::mesh {

/// A face of a cell: (cell, local face number).
struct CellFace {
  Index cell = 0;
  int face = 0;
  auto operator<=>(const CellFace&) const = default;
};

/// The layout of a structured box mesh: box cell b = i + n0 (j + n1 k) is the
/// box [origin + (i, j, k) ∘ spacing, origin + (i+1, j+1, k+1) ∘ spacing]
/// (its corners exactly: box_node). All cells are translates of each other,
/// which the non-local assembly exploits. A piece of the box (part_mesh)
/// keeps the layout with the box number of each of its cells.
struct StructuredLayout {
  std::array<Index, 3> cells{1, 1, 1};
  Vec3 origin = Vec3::Zero();
  Vec3 spacing = Vec3::Ones();
  /// The box's upper corner: its last nodes lie exactly on it.
  Vec3 upper = Vec3::Ones();
  /// The box cell of each cell of a piece, ascending; empty: cell c is box cell c.
  std::vector<Index> box_cells;

  Index num_box_cells() const { return cells[0] * cells[1] * cells[2]; }
  Index box_cell(Index c) const { return box_cells.empty() ? c : box_cells[static_cast<std::size_t>(c)]; }
  /// (i, j, k) of cell c (of the mesh: through box_cell on a piece).
  std::array<Index, 3> cell_ijk(Index c) const { return box_cell_ijk(box_cell(c)); }
  std::array<Index, 3> box_cell_ijk(Index b) const {
    return {b % cells[0], (b / cells[0]) % cells[1], b / (cells[0] * cells[1])};
  }
};

class Mesh {
 public:
  Mesh(int dim, std::vector<Vec3> nodes, std::vector<Index> cells);

  int dim() const { return dim_; }
  CellType cell_type() const { return cell_type_of_dim(dim_); }
  int nodes_per_cell() const { return mesh::nodes_per_cell(cell_type()); }
  Index num_nodes() const { return static_cast<Index>(nodes_.size()); }
  Index num_cells() const {
    return static_cast<Index>(cells_.size() / static_cast<std::size_t>(nodes_per_cell()));
  }

  const Vec3& node(Index n) const {
    assert(n >= 0 && n < num_nodes());
    return nodes_[static_cast<std::size_t>(n)];
  }
  const std::vector<Vec3>& nodes() const { return nodes_; }
  std::span<const Index> cell(Index c) const {
    assert(c >= 0 && c < num_cells());
    return {cells_.data() + static_cast<std::size_t>(c) * static_cast<std::size_t>(nodes_per_cell()),
            static_cast<std::size_t>(nodes_per_cell())};
  }
  const std::vector<Index>& connectivity() const { return cells_; }
  Vec3 cell_centroid(Index c) const;
  /// Largest edge length of cell c.
  double cell_size(Index c) const;
  /// Axis-aligned bounding box of all nodes.
  std::pair<Vec3, Vec3> bounding_box() const;

  std::map<std::string, std::vector<Index>> node_sets;
  std::map<std::string, std::vector<CellFace>> face_sets;
  std::map<std::string, std::vector<Index>> cell_sets;
  /// Region id per cell (0 by default), written to the output.
  std::vector<int> cell_region;
  /// Cuts along which nodes were split (see split_along_cut).
  std::vector<Cut> cuts;
  /// Set for structured boxes (make_box); node splitting keeps it valid.
  std::optional<StructuredLayout> structure;

  /// Node set by name, or the nodes of a face set of that name; throws
  /// InputError naming the known sets if neither exists.
  std::vector<Index> nodes_of_set(const std::string& name) const;
  /// Names of every node, face and cell set (for error messages).
  std::vector<std::string> set_names() const;

  // Mutation used by the pre-crack splitter.
  Index add_node(const Vec3& x);
  void set_cell_node(Index c, int local, Index node) {
    assert(c >= 0 && c < num_cells() && local >= 0 && local < nodes_per_cell());
    cells_[static_cast<std::size_t>(c) * static_cast<std::size_t>(nodes_per_cell()) +
           static_cast<std::size_t>(local)] = node;
  }

 private:
  int dim_;
  std::vector<Vec3> nodes_;
  std::vector<Index> cells_;
};

}  // namespace perimorph::mesh
