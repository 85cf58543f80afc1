#include "perimorph/mesh/mesh.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <set>

namespace perimorph::mesh {

Mesh::Mesh(int dim, std::vector<Vec3> nodes, std::vector<Index> cells)
    : dim_(dim), nodes_(std::move(nodes)), cells_(std::move(cells)) {
  PERIMORPH_ASSERT(dim >= 1 && dim <= 3, "mesh dimension must be 1, 2 or 3");
  PERIMORPH_ASSERT(cells_.size() % static_cast<std::size_t>(nodes_per_cell()) == 0,
                   "connectivity size is not a multiple of nodes per cell");
  for (Index n : cells_) PERIMORPH_ASSERT(n >= 0 && n < num_nodes(), "cell refers to a missing node");
  cell_region.assign(static_cast<std::size_t>(num_cells()), 0);
}

Vec3 Mesh::cell_centroid(Index c) const {
  Vec3 x = Vec3::Zero();
  for (Index n : cell(c)) x += node(n);
  return x / nodes_per_cell();
}

double Mesh::cell_size(Index c) const {
  const auto nodes = cell(c);
  double h = 0.0;
  // Edges of a tensor-product cell join local nodes that differ in one bit.
  for (int a = 0; a < nodes_per_cell(); ++a)
    for (int d = 0; d < dim_; ++d)
      if (!((a >> d) & 1))
        h = std::max(h, (node(nodes[static_cast<std::size_t>(a | (1 << d))]) -
                         node(nodes[static_cast<std::size_t>(a)]))
                            .norm());
  return h;
}

std::pair<Vec3, Vec3> Mesh::bounding_box() const {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max());
  Vec3 hi = -lo;
  for (const Vec3& x : nodes_) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return {lo, hi};
}

std::vector<Index> Mesh::nodes_of_set(const std::string& name) const {
  if (auto it = node_sets.find(name); it != node_sets.end()) return it->second;
  if (auto it = face_sets.find(name); it != face_sets.end()) {
    std::set<Index> nodes;
    for (const CellFace& cf : it->second)
      for (int a : face_nodes(cell_type(), cf.face)) nodes.insert(cell(cf.cell)[static_cast<std::size_t>(a)]);
    return {nodes.begin(), nodes.end()};
  }
  if (auto it = cell_sets.find(name); it != cell_sets.end()) {
    std::set<Index> nodes;
    for (Index c : it->second)
      for (Index n : cell(c)) nodes.insert(n);
    return {nodes.begin(), nodes.end()};
  }
  throw InputError(fmt::format("no node, face or cell set named '{}'; the mesh has: {}", name,
                               fmt::join(set_names(), ", ")));
}

std::vector<std::string> Mesh::set_names() const {
  std::set<std::string> names;
  for (const auto& [k, v] : node_sets) names.insert(k);
  for (const auto& [k, v] : face_sets) names.insert(k);
  for (const auto& [k, v] : cell_sets) names.insert(k);
  return {names.begin(), names.end()};
}

Index Mesh::add_node(const Vec3& x) {
  nodes_.push_back(x);
  return num_nodes() - 1;
}

}  // namespace perimorph::mesh
