#include "perimorph/mesh/part_mesh.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace perimorph::mesh {
namespace {

/// The position of `value` in the ascending `sorted`, or -1.
Index find_sorted(const std::vector<Index>& sorted, Index value) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), value);
  return it != sorted.end() && *it == value ? static_cast<Index>(it - sorted.begin()) : -1;
}

}  // namespace

Index PartMesh::local_cell(Index c) const {
  return find_sorted(global_cell, c);
}
Index PartMesh::local_node(Index n) const {
  return find_sorted(global_node, n);
}

PartMesh part_mesh(const Mesh& whole, std::span<const Index> cells) {
  std::vector<Index> global_cell(cells.begin(), cells.end());
  std::sort(global_cell.begin(), global_cell.end());
  for (std::size_t k = 0; k < global_cell.size(); ++k) {
    const Index c = global_cell[k];
    if (c < 0 || c >= whole.num_cells())
      throw Error(fmt::format("part mesh: cell {} is not one of the mesh's {} cells", c, whole.num_cells()));
    if (k > 0 && global_cell[k - 1] == c) throw Error(fmt::format("part mesh: cell {} is listed twice", c));
  }

  // The cells' node entries sorted by global node (each with its place in
  // the connectivity): the local nodes in global order, and each entry's
  // local node, in one sweep.
  const auto k = static_cast<std::size_t>(whole.nodes_per_cell());
  std::vector<std::pair<Index, Index>> entries;
  entries.reserve(global_cell.size() * k);
  for (std::size_t c = 0; c < global_cell.size(); ++c) {
    const auto nodes = whole.cell(global_cell[c]);
    for (std::size_t a = 0; a < k; ++a) entries.emplace_back(nodes[a], static_cast<Index>(c * k + a));
  }
  std::sort(entries.begin(), entries.end());
  std::vector<Index> global_node, connectivity(entries.size());
  std::vector<Vec3> nodes;
  for (const auto& [n, at] : entries) {
    if (global_node.empty() || global_node.back() != n) {
      global_node.push_back(n);
      nodes.push_back(whole.node(n));
    }
    connectivity[static_cast<std::size_t>(at)] = static_cast<Index>(global_node.size()) - 1;
  }
  entries = {};

  PartMesh out{Mesh(whole.dim(), std::move(nodes), std::move(connectivity)), std::move(global_cell),
               std::move(global_node)};
  Mesh& mesh = out.mesh;
  for (std::size_t c = 0; c < out.global_cell.size(); ++c)
    mesh.cell_region[c] = whole.cell_region[static_cast<std::size_t>(out.global_cell[c])];
  mesh.cuts = whole.cuts;
  if (whole.structure) {
    mesh.structure = whole.structure;
    auto& box = mesh.structure->box_cells;
    box.clear();
    for (Index g : out.global_cell) box.push_back(whole.structure->box_cell(g));
  }

  for (const auto& [name, set] : whole.node_sets) {
    auto& mine = mesh.node_sets[name];
    for (Index n : set)
      if (const Index l = out.local_node(n); l >= 0) mine.push_back(l);
  }
  for (const auto& [name, set] : whole.face_sets) {
    auto& mine = mesh.face_sets[name];
    for (const CellFace& f : set)
      if (const Index l = out.local_cell(f.cell); l >= 0) mine.push_back({l, f.face});
  }
  for (const auto& [name, set] : whole.cell_sets) {
    auto& mine = mesh.cell_sets[name];
    for (Index c : set)
      if (const Index l = out.local_cell(c); l >= 0) mine.push_back(l);
  }
  return out;
}

}  // namespace perimorph::mesh
