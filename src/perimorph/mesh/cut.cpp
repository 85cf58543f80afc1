#include "perimorph/mesh/cut.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace perimorph::mesh {

namespace {

using FaceKey = std::vector<Index>;

FaceKey face_key(const Mesh& mesh, Index c, int f) {
  FaceKey key;
  for (int a : face_nodes(mesh.cell_type(), f)) key.push_back(mesh.cell(c)[static_cast<std::size_t>(a)]);
  std::sort(key.begin(), key.end());
  return key;
}

struct UnionFind {
  std::map<Index, Index> parent;
  Index find(Index x) {
    auto it = parent.find(x);
    if (it == parent.end()) return parent[x] = x;
    if (it->second == x) return x;
    return it->second = find(it->second);
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

/// Splits the nodes of the interior faces `cut_faces` (keys of sorted node
/// numbers; `faces` maps every face key of the mesh to its owners).
CutReport split_faces(Mesh& mesh, const std::set<FaceKey>& cut_faces,
                      const std::map<FaceKey, std::vector<CellFace>>& faces,
                      const std::vector<std::vector<Index>>& node_cells) {
  std::set<Index> cut_nodes;
  for (const FaceKey& key : cut_faces) cut_nodes.insert(key.begin(), key.end());

  // Decide every split on the original connectivity, then apply.
  std::vector<std::pair<Index, std::vector<std::vector<Index>>>> splits;  // node, extra components
  for (Index n : cut_nodes) {
    const auto& cells = node_cells[static_cast<std::size_t>(n)];
    UnionFind uf;
    for (Index c : cells) {
      uf.find(c);
      for (int f = 0; f < faces_per_cell(mesh.cell_type()); ++f) {
        FaceKey key = face_key(mesh, c, f);
        if (!std::binary_search(key.begin(), key.end(), n) || cut_faces.count(key)) continue;
        const auto& owners = faces.at(key);
        if (owners.size() == 2) uf.unite(owners[0].cell, owners[1].cell);
      }
    }
    std::map<Index, std::vector<Index>> components;
    for (Index c : cells) components[uf.find(c)].push_back(c);
    if (components.size() < 2) continue;
    std::vector<std::vector<Index>> extra;
    for (auto it = std::next(components.begin()); it != components.end(); ++it) extra.push_back(it->second);
    splits.emplace_back(n, std::move(extra));
  }

  CutReport report;
  report.faces_cut = static_cast<Index>(cut_faces.size());
  std::map<Index, std::vector<Index>> copies;
  for (const auto& [n, extra] : splits) {
    for (const auto& component : extra) {
      const Index copy = mesh.add_node(mesh.node(n));
      copies[n].push_back(copy);
      ++report.nodes_split;
      for (Index c : component) {
        const auto nodes = mesh.cell(c);
        for (int a = 0; a < mesh.nodes_per_cell(); ++a)
          if (nodes[static_cast<std::size_t>(a)] == n) mesh.set_cell_node(c, a, copy);
      }
    }
  }
  for (auto& [name, set] : mesh.node_sets) {
    std::vector<Index> added;
    for (Index n : set)
      if (auto it = copies.find(n); it != copies.end())
        added.insert(added.end(), it->second.begin(), it->second.end());
    set.insert(set.end(), added.begin(), added.end());
    std::sort(set.begin(), set.end());
  }
  return report;
}

/// Every face of the mesh by key, with its owners, and the cells of each node.
struct FaceIndex {
  std::map<FaceKey, std::vector<CellFace>> faces;
  std::vector<std::vector<Index>> node_cells;
  explicit FaceIndex(const Mesh& mesh) : node_cells(static_cast<std::size_t>(mesh.num_nodes())) {
    for (Index c = 0; c < mesh.num_cells(); ++c) {
      for (int f = 0; f < faces_per_cell(mesh.cell_type()); ++f)
        faces[face_key(mesh, c, f)].push_back({c, f});
      for (Index n : mesh.cell(c)) node_cells[static_cast<std::size_t>(n)].push_back(c);
    }
  }
};

/// The face as cut geometry: a point (1D), a segment (2D) or two triangles (3D;
/// the quad a0 a1 a3 a2 split along a1–a2).
void append_pieces(const Mesh& mesh, const CellFace& cf, std::vector<Cut>& cuts) {
  std::vector<Vec3> x;
  for (int a : face_nodes(mesh.cell_type(), cf.face))
    x.push_back(mesh.node(mesh.cell(cf.cell)[static_cast<std::size_t>(a)]));
  const int dim = mesh.dim();
  if (dim == 1) {
    cuts.push_back(Cut{1, x[0], Vec3::Zero(), Vec3::Zero()});
  } else if (dim == 2) {
    cuts.push_back(Cut{2, x[0], x[1] - x[0], Vec3::Zero()});
  } else {
    cuts.push_back(Cut{3, x[0], x[1] - x[0], x[2] - x[0], true});
    cuts.push_back(Cut{3, x[3], x[2] - x[3], x[1] - x[3], true});
  }
}

}  // namespace

CutReport split_along_cut(Mesh& mesh, const Cut& cut) {
  double hmin = std::numeric_limits<double>::max();
  for (Index c = 0; c < mesh.num_cells(); ++c) hmin = std::min(hmin, mesh.cell_size(c));
  const double tol = 1e-8 * hmin;

  const FaceIndex index(mesh);

  std::set<FaceKey> cut_faces;
  for (const auto& [key, owners] : index.faces) {
    if (owners.size() != 2) continue;
    if (std::all_of(key.begin(), key.end(), [&](Index n) { return cut.contains(mesh.node(n), tol); }))
      cut_faces.insert(key);
  }
  if (cut_faces.empty())
    throw InputError(
        "the pre-crack cut does not lie on any interior element face: a cut must follow "
        "element faces (place it on a grid line/plane of the mesh)");

  CutReport report = split_faces(mesh, cut_faces, index.faces, index.node_cells);
  mesh.cuts.push_back(cut);
  return report;
}

CutReport split_along_faces(Mesh& mesh, const std::vector<CellFace>& faces) {
  const FaceIndex index(mesh);
  std::set<FaceKey> cut_faces, seen;
  std::vector<Cut> pieces;
  for (const CellFace& cf : faces) {
    FaceKey key = face_key(mesh, cf.cell, cf.face);
    if (!seen.insert(key).second) continue;
    append_pieces(mesh, cf, pieces);
    if (index.faces.at(key).size() == 2) cut_faces.insert(std::move(key));
  }
  CutReport report;
  if (!cut_faces.empty()) report = split_faces(mesh, cut_faces, index.faces, index.node_cells);
  mesh.cuts.insert(mesh.cuts.end(), pieces.begin(), pieces.end());
  return report;
}

}  // namespace perimorph::mesh
