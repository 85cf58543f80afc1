#include "perimorph/setup/mesh_window.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box_window.hpp"
#include "perimorph/partition/grid_bisection.hpp"
#include "perimorph/setup/discretization.hpp"

#include <algorithm>
#include <cmath>

namespace perimorph::setup {

mesh::BoxSpec box_of(const casefile::CaseConfig& config) {
  const auto& box = config.mesh.box;
  return {box.dim, box.lower, box.upper, box.cells};
}

partition::GridBisection grid_bisection(const casefile::CaseConfig& config, int parts) {
  const mesh::BoxSpec spec = box_of(config);
  return {mesh::box_layout(spec), spec.dim, parts};
}

bool has_windows(const casefile::CaseConfig& config) {
  return config.mesh.kind == casefile::MeshKind::box && config.mesh.holes.empty() && config.mesh.cuts.empty();
}

MeshWindow part_window(const casefile::CaseConfig& config, const partition::GridBisection& grid, int part) {
  const mesh::BoxSpec spec = box_of(config);
  const mesh::StructuredLayout layout = mesh::box_layout(spec);
  const Vec3 h = layout.spacing;
  double diagonal = 0.0, h_min = h[0];
  for (int d = 0; d < spec.dim; ++d) {
    diagonal += h[d] * h[d];
    h_min = std::min(h_min, h[d]);
  }
  diagonal = std::sqrt(diagonal);
  const double delta = config.nonlocal.enabled ? config.nonlocal.horizon : 0.0;
  const bool matrix_free = config.solver.op == casefile::SolverOperator::matrix_free;
  auto [lo, hi] = grid.bounds(part);
  for (int d = 0; d < spec.dim; ++d) {
    const auto du = static_cast<std::size_t>(d);
    Index reach = 0;
    if (config.nonlocal.enabled)
      reach = matrix_free ? static_cast<Index>(std::ceil(delta / h_min)) + 1
                          : static_cast<Index>(std::ceil((delta + diagonal) / h[d]));
    const Index width = 1 + reach + 1;
    lo[du] = std::max<Index>(lo[du] - width, 0);
    hi[du] = std::min<Index>(hi[du] + width, layout.cells[du]);
  }
  MeshWindow w;
  w.lo = lo;
  w.hi = hi;
  for (Index c : mesh::box_window_cells(spec, lo, hi)) w.owner.push_back(grid.owner(c));
  return w;
}

mesh::Mesh window_mesh(const casefile::CaseConfig& config, const MeshWindow& w,
                       std::shared_ptr<WindowNumbers>& numbers) {
  PERIMORPH_ASSERT(has_windows(config), "a part on a window needs a box mesh without holes or cuts");
  const mesh::BoxSpec spec = box_of(config);
  mesh::PartMesh pm = mesh::make_box_window(spec, w.lo, w.hi);
  numbers = std::make_shared<WindowNumbers>();
  numbers->lo = w.lo;
  numbers->hi = w.hi;
  numbers->whole_cells = pm.mesh.structure->num_box_cells();
  numbers->whole_nodes = 1;
  for (int d = 0; d < spec.dim; ++d) numbers->whole_nodes *= spec.cells[static_cast<std::size_t>(d)] + 1;
  numbers->global_cell = std::move(pm.global_cell);
  numbers->global_node = std::move(pm.global_node);
  PERIMORPH_ASSERT(w.owner.size() == numbers->global_cell.size(), "a part for every cell of the window");
  // The whole box's bounds: make_box places its first and last nodes on them.
  return shape_mesh(config, std::move(pm.mesh), {w.any_over_processes, std::pair{spec.lower, spec.upper}});
}

}  // namespace perimorph::setup
