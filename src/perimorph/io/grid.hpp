#pragma once
// Plain data handed to the output stage: an unstructured grid of one cell type
// with named point and cell fields. io/ knows nothing about meshes or
// solvers; whoever owns the data fills this struct and calls write_vtu().

#include "perimorph/core/types.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace perimorph::io {

/// A named field with `components` values per entity (point or cell), stored
/// entity-major: values[e * components + c]. Contract: components >= 1,
/// values.size() == count * components, name non-empty and unique within its
/// point_data or cell_data list.
struct Field {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// VTK cell type ids (vtkCellType.h) of the cells perimorph writes.
enum class VtkCell : std::uint8_t { line = 3, quad = 9, hexahedron = 12, vertex = 1 };

/// Nodes of one cell of type t.
constexpr int vtk_nodes_per_cell(VtkCell t) {
  switch (t) {
    case VtkCell::vertex:
      return 1;
    case VtkCell::line:
      return 2;
    case VtkCell::quad:
      return 4;
    case VtkCell::hexahedron:
      return 8;
  }
  return 0;
}

/// One piece of an unstructured grid, all cells of the same type.
///
/// `connectivity` lists nodes_per_cell point indices per cell in perimorph's
/// local order: lexicographic, x fastest, i.e. quad (-1,-1),(1,-1),(-1,1),(1,1)
/// and hex likewise with z slowest. The writer permutes quads and hexes into
/// VTK's counter-clockwise order; callers never do. Contract:
/// nodes_per_cell == vtk_nodes_per_cell(cell_type), connectivity.size() is a
/// multiple of it, every index is in [0, points.size()), point fields have
/// points.size() entities and cell fields connectivity.size() / nodes_per_cell.
struct UnstructuredGrid {
  std::vector<Vec3> points;
  std::vector<Index> connectivity;
  int nodes_per_cell = 0;
  VtkCell cell_type = VtkCell::vertex;
  std::vector<Field> point_data;
  std::vector<Field> cell_data;
};

}  // namespace perimorph::io
