#include "perimorph/mesh/holes.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <utility>

namespace perimorph::mesh {

namespace {

/// The entries of `set` that `map` keeps (map[i] >= 0), renumbered; order kept.
std::vector<Index> remap(const std::vector<Index>& set, const std::vector<Index>& map) {
  std::vector<Index> out;
  out.reserve(set.size());
  for (Index i : set)
    if (const Index j = map[static_cast<std::size_t>(i)]; j >= 0) out.push_back(j);
  return out;
}

}  // namespace

void remove_cells(Mesh& mesh, const std::vector<char>& remove) {
  PERIMORPH_ASSERT(remove.size() == static_cast<std::size_t>(mesh.num_cells()),
                   "remove_cells needs one flag per cell");
  const auto ncells = static_cast<std::size_t>(mesh.num_cells());
  const auto nnodes = static_cast<std::size_t>(mesh.num_nodes());

  std::vector<Index> cell_map(ncells, -1);
  std::vector<Index> node_map(nnodes, -1);
  Index kept_cells = 0;
  for (std::size_t c = 0; c < ncells; ++c) {
    if (remove[c]) continue;
    cell_map[c] = kept_cells++;
    for (Index n : mesh.cell(static_cast<Index>(c))) node_map[static_cast<std::size_t>(n)] = 0;
  }
  Index kept_nodes = 0;
  std::vector<Vec3> nodes;
  for (std::size_t n = 0; n < nnodes; ++n)
    if (node_map[n] == 0) {
      node_map[n] = kept_nodes++;
      nodes.push_back(mesh.node(static_cast<Index>(n)));
    }
  std::vector<Index> connectivity;
  connectivity.reserve(static_cast<std::size_t>(kept_cells) *
                       static_cast<std::size_t>(mesh.nodes_per_cell()));
  std::vector<int> region;
  region.reserve(static_cast<std::size_t>(kept_cells));
  for (std::size_t c = 0; c < ncells; ++c) {
    if (cell_map[c] < 0) continue;
    for (Index n : mesh.cell(static_cast<Index>(c)))
      connectivity.push_back(node_map[static_cast<std::size_t>(n)]);
    region.push_back(mesh.cell_region[c]);
  }

  Mesh out(mesh.dim(), std::move(nodes), std::move(connectivity));
  for (const auto& [name, set] : mesh.node_sets) out.node_sets[name] = remap(set, node_map);
  for (const auto& [name, set] : mesh.cell_sets) out.cell_sets[name] = remap(set, cell_map);
  for (const auto& [name, set] : mesh.face_sets) {
    std::vector<CellFace>& faces = out.face_sets[name];
    for (const CellFace& f : set)
      if (const Index c = cell_map[static_cast<std::size_t>(f.cell)]; c >= 0) faces.push_back({c, f.face});
  }
  out.cell_region = std::move(region);
  out.cuts = std::move(mesh.cuts);
  out.structure.reset();  // cell c is no longer cell (i, j, k) of the grid
  mesh = std::move(out);
}

Index remove_hole(Mesh& mesh, const Hole& hole) {
  std::vector<char> remove(static_cast<std::size_t>(mesh.num_cells()), 0);
  Index count = 0;
  for (Index c = 0; c < mesh.num_cells(); ++c)
    if (hole.contains(mesh.cell_centroid(c))) {
      remove[static_cast<std::size_t>(c)] = 1;
      ++count;
    }
  if (count == 0)
    throw InputError(fmt::format(
        "the hole ({}) contains no cell centroid, so it removes nothing; enlarge it, move it onto the mesh "
        "or refine the mesh",
        hole.describe()));
  if (count == mesh.num_cells())
    throw InputError(fmt::format(
        "the hole ({}) contains the centroid of every cell ({}), so no mesh would remain; make it smaller",
        hole.describe(), count));
  remove_cells(mesh, remove);
  return count;
}

}  // namespace perimorph::mesh
