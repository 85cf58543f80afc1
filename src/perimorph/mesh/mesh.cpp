#include "perimorph/mesh/mesh.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Dense>

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

// ---------------------------------------------------------------------------
// Cut geometry

Vec3 Cut::normal() const {
  if (dim == 1) return Vec3::UnitX();
  if (dim == 2) return Vec3(-edge1.y(), edge1.x(), 0.0).normalized();
  return edge1.cross(edge2).normalized();
}

namespace {
/// Coordinates (s, t) of p's projection on the cut in the basis (edge1, edge2).
std::pair<double, double> in_plane_coordinates(const Cut& cut, const Vec3& p) {
  const Vec3 r = p - cut.origin;
  if (cut.dim == 2) return {r.dot(cut.edge1) / cut.edge1.squaredNorm(), 0.0};
  Eigen::Matrix2d g;
  g << cut.edge1.dot(cut.edge1), cut.edge1.dot(cut.edge2), cut.edge2.dot(cut.edge1), cut.edge2.dot(cut.edge2);
  const Eigen::Vector2d st = g.ldlt().solve(Eigen::Vector2d(r.dot(cut.edge1), r.dot(cut.edge2)));
  return {st[0], st[1]};
}
}  // namespace

bool Cut::contains(const Vec3& p, double tol) const {
  if (dim == 1) return std::abs(p.x() - origin.x()) <= tol;
  if (std::abs((p - origin).dot(normal())) > tol) return false;
  auto [s, t] = in_plane_coordinates(*this, p);
  const double ts = tol / edge1.norm();
  if (s < -ts || s > 1 + ts) return false;
  if (dim == 3) {
    const double tt = tol / edge2.norm();
    if (t < -tt || t > 1 + tt) return false;
  }
  return true;
}

bool Cut::crosses(const Vec3& a, const Vec3& b) const {
  const Vec3 n = normal();
  const double da = (a - origin).dot(n);
  const double db = (b - origin).dot(n);
  if ((da > 0 && db > 0) || (da < 0 && db < 0)) return false;
  if (da == db) return false;  // parallel to (or inside) the cut: does not cross it
  const Vec3 p = a + (b - a) * (da / (da - db));
  if (dim == 1) return true;
  // The cut is closed: a segment through its boundary crosses it. The
  // crossing point carries round-off, so s and t are compared with a margin
  // of kEdgeTie (in units of the edge lengths); without it, mirror-image bonds
  // through the edge would be decided by the last bit of p.
  constexpr double kEdgeTie = 1e-12;
  auto [s, t] = in_plane_coordinates(*this, p);
  if (s < -kEdgeTie || s > 1 + kEdgeTie) return false;
  return dim == 2 || (t >= -kEdgeTie && t <= 1 + kEdgeTie);
}

}  // namespace perimorph::mesh
