#pragma once
// Reference cells: 1D two-node bars, 2D four-node quads, 3D eight-node hexes
// (THEORY §4). Local node numbering is lexicographic in the reference
// coordinates, x fastest: quad (-1,-1),(1,-1),(-1,1),(1,1); hex likewise with z
// slowest. Reference coordinates live in [-1, 1]^d.

#include <array>
#include <span>

namespace perimorph::mesh {

enum class CellType { bar2, quad4, hex8 };

constexpr int cell_dim(CellType t) {
  return t == CellType::bar2 ? 1 : t == CellType::quad4 ? 2 : 3;
}
constexpr int nodes_per_cell(CellType t) {
  return 1 << cell_dim(t);
}
constexpr int faces_per_cell(CellType t) {
  return 2 * cell_dim(t);
}
constexpr int nodes_per_face(CellType t) {
  return nodes_per_cell(t) / 2;
}
constexpr CellType cell_type_of_dim(int dim) {
  return dim == 1 ? CellType::bar2 : dim == 2 ? CellType::quad4 : CellType::hex8;
}

/// Local nodes of local face f. Faces are numbered -x, +x, -y, +y, -z, +z, so
/// face f has outward normal along axis f/2 with sign (f odd ? + : -).
std::span<const int> face_nodes(CellType t, int f);

/// Reference coordinate (±1) of local node a along axis d.
constexpr double reference_node_coordinate(int a, int d) {
  return ((a >> d) & 1) ? 1.0 : -1.0;
}

}  // namespace perimorph::mesh
