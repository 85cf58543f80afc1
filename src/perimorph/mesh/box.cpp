#include "perimorph/mesh/box.hpp"

#include "perimorph/core/error.hpp"

#include <set>

namespace perimorph::mesh {

Mesh make_box(const BoxSpec& spec) {
  const int dim = spec.dim;
  PERIMORPH_ASSERT(dim >= 1 && dim <= 3, "box dimension");
  std::array<Index, 3> n{1, 1, 1};   // cells per direction
  std::array<Index, 3> nn{1, 1, 1};  // nodes per direction
  for (int d = 0; d < dim; ++d) {
    n[static_cast<std::size_t>(d)] = spec.cells[static_cast<std::size_t>(d)];
    PERIMORPH_ASSERT(n[static_cast<std::size_t>(d)] >= 1, "box needs at least one cell per direction");
    nn[static_cast<std::size_t>(d)] = n[static_cast<std::size_t>(d)] + 1;
  }
  auto node_id = [&](Index i, Index j, Index k) { return i + nn[0] * (j + nn[1] * k); };
  const StructuredLayout layout = box_layout(spec);

  std::vector<Vec3> nodes;
  nodes.reserve(static_cast<std::size_t>(nn[0] * nn[1] * nn[2]));
  for (Index k = 0; k < nn[2]; ++k)
    for (Index j = 0; j < nn[1]; ++j)
      for (Index i = 0; i < nn[0]; ++i) nodes.push_back(box_node(layout, dim, {i, j, k}));

  const int npc = nodes_per_cell(cell_type_of_dim(dim));
  std::vector<Index> cells;
  cells.reserve(static_cast<std::size_t>(n[0] * n[1] * n[2] * npc));
  for (Index k = 0; k < n[2]; ++k)
    for (Index j = 0; j < n[1]; ++j)
      for (Index i = 0; i < n[0]; ++i)
        for (int a = 0; a < npc; ++a)
          cells.push_back(node_id(i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1)));

  Mesh mesh(dim, std::move(nodes), std::move(cells));

  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  std::set<Index> boundary_nodes;
  std::vector<CellFace> boundary_faces;
  for (int d = 0; d < dim; ++d) {
    const auto du = static_cast<std::size_t>(d);
    for (int side = 0; side < 2; ++side) {
      const Index plane = side == 0 ? 0 : n[du];
      std::vector<Index> set_nodes;
      for (Index k = 0; k < nn[2]; ++k)
        for (Index j = 0; j < nn[1]; ++j)
          for (Index i = 0; i < nn[0]; ++i) {
            const std::array<Index, 3> ijk{i, j, k};
            if (ijk[du] == plane) set_nodes.push_back(node_id(i, j, k));
          }
      std::vector<CellFace> set_faces;
      const Index cell_plane = side == 0 ? 0 : n[du] - 1;
      for (Index k = 0; k < n[2]; ++k)
        for (Index j = 0; j < n[1]; ++j)
          for (Index i = 0; i < n[0]; ++i) {
            const std::array<Index, 3> ijk{i, j, k};
            if (ijk[du] == cell_plane) set_faces.push_back({i + n[0] * (j + n[1] * k), 2 * d + side});
          }
      boundary_nodes.insert(set_nodes.begin(), set_nodes.end());
      boundary_faces.insert(boundary_faces.end(), set_faces.begin(), set_faces.end());
      mesh.node_sets[names[d][side]] = std::move(set_nodes);
      mesh.face_sets[names[d][side]] = std::move(set_faces);
    }
  }
  mesh.node_sets["boundary"] = {boundary_nodes.begin(), boundary_nodes.end()};
  mesh.face_sets["boundary"] = std::move(boundary_faces);
  std::vector<Index> all(static_cast<std::size_t>(mesh.num_cells()));
  for (Index c = 0; c < mesh.num_cells(); ++c) all[static_cast<std::size_t>(c)] = c;
  mesh.cell_sets["all"] = std::move(all);
  mesh.structure = layout;
  return mesh;
}

StructuredLayout box_layout(const BoxSpec& spec) {
  StructuredLayout layout;
  for (int d = 0; d < spec.dim; ++d)
    layout.cells[static_cast<std::size_t>(d)] = spec.cells[static_cast<std::size_t>(d)];
  layout.origin = spec.lower;
  layout.upper = spec.upper;
  for (int d = 0; d < spec.dim; ++d)
    layout.spacing[d] =
        (spec.upper[d] - spec.lower[d]) / static_cast<double>(layout.cells[static_cast<std::size_t>(d)]);
  return layout;
}

Vec3 box_node(const StructuredLayout& layout, int dim, const std::array<Index, 3>& ijk) {
  Vec3 x = Vec3::Zero();
  for (int d = 0; d < dim; ++d) {
    const auto du = static_cast<std::size_t>(d);
    const Index n = layout.cells[du];
    // Last node exactly on the upper bound (no accumulated round-off).
    const double t = static_cast<double>(ijk[du]) / static_cast<double>(n);
    x[d] = ijk[du] == n ? layout.upper[d] : layout.origin[d] + t * (layout.upper[d] - layout.origin[d]);
  }
  return x;
}

Mesh box_cell_mesh(const StructuredLayout& layout, int dim, Index b) {
  PERIMORPH_ASSERT(b >= 0 && b < layout.num_box_cells(), "a cell of the box");
  const auto [i, j, k] = layout.box_cell_ijk(b);
  const int npc = nodes_per_cell(cell_type_of_dim(dim));
  std::vector<Vec3> corners;
  std::vector<Index> cell;
  for (int a = 0; a < npc; ++a) {
    corners.push_back(box_node(layout, dim, {i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1)}));
    cell.push_back(a);
  }
  return Mesh(dim, std::move(corners), std::move(cell));
}

}  // namespace perimorph::mesh
