#include "perimorph/diagnostics/model_memory.hpp"

#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"

namespace perimorph::diagnostics {

namespace {

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

}  // namespace

ModelMemory model_memory(const setup::Discretization& model) {
  ModelMemory m;
  const auto& mesh = model.mesh;
  m.mesh = bytes_of(mesh.nodes()) + bytes_of(mesh.connectivity()) + bytes_of(mesh.cell_region);
  for (const auto& [name, set] : mesh.node_sets) m.mesh += bytes_of(set);
  for (const auto& [name, set] : mesh.cell_sets) m.mesh += bytes_of(set);
  for (const auto& [name, set] : mesh.face_sets) m.mesh += bytes_of(set);
  const auto& dm = model.dofmap;
  const auto cells = static_cast<std::size_t>(dm.num_cells());
  std::size_t cell_nodes = 0;
  for (Index c = 0; c < dm.num_cells(); ++c) cell_nodes += dm.cell_nodes(c).size();
  // Offsets and cell nodes, a flag per cell, a mesh node (or centroid's cell) per dof node.
  m.dofs = (cells + 1 + cell_nodes) * sizeof(Index) + cells * sizeof(dofs::Continuity) +
           static_cast<std::size_t>(dm.num_nodes()) * sizeof(Index);
  m.displacement = static_cast<std::size_t>(dm.num_dofs()) * sizeof(double);
  m.distribution = static_cast<std::size_t>(dm.num_nodes()) * sizeof(Index);
  m.stiffness = model.stiffness.bytes();
  if (const auto& piece = model.piece)
    m.piece_maps = bytes_of(piece->global_cell) + bytes_of(piece->global_node) + bytes_of(piece->owner) +
                   bytes_of(piece->dofs.key) + bytes_of(piece->dofs.owned);
  if (model.nonlocal) {
    const auto& nl = *model.nonlocal;
    const auto& p = nl.points;
    m.points = bytes_of(p.x) + bytes_of(p.weight) + bytes_of(p.alpha) + bytes_of(p.half) + bytes_of(p.stored);
    m.cell_alpha = bytes_of(p.cell_alpha_max) + bytes_of(p.cell_alpha_min) + bytes_of(p.slot) +
                   bytes_of(p.shape) + bytes_of(p.rule) + bytes_of(p.line_weights);
    m.graph = bytes_of(nl.graph.offsets) + bytes_of(nl.graph.neighbors);
    m.flags = bytes_of(nl.morph.purely_nonlocal);
  }
  return m;
}

}  // namespace perimorph::diagnostics
