#include "perimorph/mesh/box_window.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

namespace perimorph::mesh {

namespace {

/// Cells per axis of the box (1 beyond its dimension), and the window checked against them.
std::array<Index, 3> box_cells(const BoxSpec& spec, std::array<Index, 3>& lo, std::array<Index, 3>& hi) {
  std::array<Index, 3> n{1, 1, 1};
  for (std::size_t d = 0; d < 3; ++d) {
    if (static_cast<int>(d) < spec.dim) {
      n[d] = spec.cells[d];
    } else {
      lo[d] = 0;
      hi[d] = 1;
    }
    if (lo[d] < 0 || hi[d] > n[d] || lo[d] >= hi[d])
      throw Error(fmt::format("box window: cells [{}, {}) along axis {} are not a range of the box's {}",
                              lo[d], hi[d], d, n[d]));
  }
  return n;
}

}  // namespace

std::vector<Index> box_window_cells(const BoxSpec& spec, std::array<Index, 3> lo, std::array<Index, 3> hi) {
  const std::array<Index, 3> n = box_cells(spec, lo, hi);
  std::vector<Index> cells;
  cells.reserve(static_cast<std::size_t>((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])));
  for (Index k = lo[2]; k < hi[2]; ++k)
    for (Index j = lo[1]; j < hi[1]; ++j)
      for (Index i = lo[0]; i < hi[0]; ++i) cells.push_back(i + n[0] * (j + n[1] * k));
  return cells;
}

PartMesh make_box_window(const BoxSpec& spec, std::array<Index, 3> lo, std::array<Index, 3> hi) {
  const int dim = spec.dim;
  const std::array<Index, 3> n = box_cells(spec, lo, hi);
  std::array<Index, 3> nn{1, 1, 1}, w{1, 1, 1}, wn{1, 1, 1};  // whole nodes, window cells and nodes
  for (std::size_t d = 0; d < 3; ++d) {
    w[d] = hi[d] - lo[d];
    if (static_cast<int>(d) < dim) {
      nn[d] = n[d] + 1;
      wn[d] = w[d] + 1;
    }
  }
  // make_box's layout (the whole box's), then the window's box cells.
  StructuredLayout layout = box_layout(spec);

  std::vector<Index> global_node;
  std::vector<Vec3> nodes;
  for (Index k = lo[2]; k < lo[2] + wn[2]; ++k)
    for (Index j = lo[1]; j < lo[1] + wn[1]; ++j)
      for (Index i = lo[0]; i < lo[0] + wn[0]; ++i) {
        global_node.push_back(i + nn[0] * (j + nn[1] * k));
        nodes.push_back(box_node(layout, dim, {i, j, k}));
      }
  auto local_node = [&](Index i, Index j, Index k) {
    return i - lo[0] + wn[0] * (j - lo[1] + wn[1] * (k - lo[2]));
  };
  const int npc = nodes_per_cell(cell_type_of_dim(dim));
  std::vector<Index> connectivity;
  connectivity.reserve(static_cast<std::size_t>(w[0] * w[1] * w[2] * npc));
  for (Index k = lo[2]; k < hi[2]; ++k)
    for (Index j = lo[1]; j < hi[1]; ++j)
      for (Index i = lo[0]; i < hi[0]; ++i)
        for (int a = 0; a < npc; ++a)
          connectivity.push_back(local_node(i + (a & 1), j + ((a >> 1) & 1), k + ((a >> 2) & 1)));

  PartMesh out{Mesh(dim, std::move(nodes), std::move(connectivity)), box_window_cells(spec, lo, hi),
               std::move(global_node)};
  Mesh& mesh = out.mesh;
  layout.box_cells = out.global_cell;
  mesh.structure = std::move(layout);

  // make_box's sets, each cut to the window in the whole set's order.
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  std::vector<char> on_boundary(out.global_node.size(), 0);
  std::vector<CellFace> boundary_faces;
  for (int d = 0; d < dim; ++d) {
    const auto du = static_cast<std::size_t>(d);
    for (int side = 0; side < 2; ++side) {
      std::vector<Index> set_nodes;
      const Index plane = side == 0 ? 0 : n[du];
      for (Index k = lo[2]; k < lo[2] + wn[2]; ++k)
        for (Index j = lo[1]; j < lo[1] + wn[1]; ++j)
          for (Index i = lo[0]; i < lo[0] + wn[0]; ++i)
            if (std::array<Index, 3>{i, j, k}[du] == plane) set_nodes.push_back(local_node(i, j, k));
      std::vector<CellFace> set_faces;
      const Index cell_plane = side == 0 ? 0 : n[du] - 1;
      Index c = 0;
      for (Index k = lo[2]; k < hi[2]; ++k)
        for (Index j = lo[1]; j < hi[1]; ++j)
          for (Index i = lo[0]; i < hi[0]; ++i, ++c)
            if (std::array<Index, 3>{i, j, k}[du] == cell_plane) set_faces.push_back({c, 2 * d + side});
      for (Index v : set_nodes) on_boundary[static_cast<std::size_t>(v)] = 1;
      boundary_faces.insert(boundary_faces.end(), set_faces.begin(), set_faces.end());
      mesh.node_sets[names[d][side]] = std::move(set_nodes);
      mesh.face_sets[names[d][side]] = std::move(set_faces);
    }
  }
  auto& boundary = mesh.node_sets["boundary"];
  for (std::size_t v = 0; v < on_boundary.size(); ++v)
    if (on_boundary[v]) boundary.push_back(static_cast<Index>(v));
  mesh.face_sets["boundary"] = std::move(boundary_faces);
  auto& all = mesh.cell_sets["all"];
  for (Index c = 0; c < mesh.num_cells(); ++c) all.push_back(c);
  return out;
}

}  // namespace perimorph::mesh
