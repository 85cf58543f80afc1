#include "perimorph/system/matrix_free_stiffness.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/system/stiffness.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace perimorph::system {

assembly::OffsetBlocks grid_offset_blocks(const casefile::CaseConfig& config,
                                          const mesh::StructuredLayout& layout) {
  const int dim = config.dim();
  casefile::CaseConfig patch = config;
  // Every bond of the centre cell inside the patch: the horizon, plus one cell
  // for partial volumes (a point's box reaches half a cell beyond it).
  const double h = layout.spacing.head(dim).minCoeff();
  const auto r = static_cast<Index>(std::ceil(config.nonlocal.horizon / h)) + 1;
  const Index m = 2 * r + 3;
  patch.mesh.box.cells.fill(1);
  for (int d = 0; d < dim; ++d) {
    patch.mesh.box.cells[static_cast<std::size_t>(d)] = m;
    patch.mesh.box.upper[d] = patch.mesh.box.lower[d] + static_cast<double>(m) * layout.spacing[d];
  }
  patch.solver.op = casefile::SolverOperator::assembled;
  patch.dirichlet.clear();
  patch.tractions.clear();
  patch.node_sets.clear();
  patch.regions.clear();
  for (auto& material : patch.materials) material.region = "all";
  patch.loading = {};
  const setup::Discretization small = setup::build_discretization(patch);
  Index centre = 0;
  for (int d = dim - 1; d >= 0; --d) centre = centre * m + m / 2;
  return assembly::offset_blocks(small.nonlocal_space(), centre);
}

MatrixFreeStiffness build_matrix_free_stiffness(const setup::Discretization& model) {
  const auto& config = model.config;
  PERIMORPH_ASSERT(config.solver.op == casefile::SolverOperator::matrix_free && model.mesh.structure,
                   "build_matrix_free_stiffness needs a matrix-free case on a box grid");
  const auto& layout = *model.mesh.structure;
  // The operator's window: the grid, or on a process's piece the box of its cells.
  assembly::GridWindow window{{0, 0, 0}, layout.cells};
  if (model.piece) {
    std::array<Index, 3> hi{0, 0, 0};
    window.lo = layout.cells;
    for (Index c = 0; c < model.mesh.num_cells(); ++c) {
      const auto ijk = layout.cell_ijk(c);
      for (std::size_t d = 0; d < 3; ++d) {
        window.lo[d] = std::min(window.lo[d], ijk[d]);
        hi[d] = std::max(hi[d], ijk[d] + 1);
      }
    }
    for (std::size_t d = 0; d < 3; ++d) window.size[d] = std::max<Index>(hi[d] - window.lo[d], 0);
  }
  std::vector<Index> node_of_cell(static_cast<std::size_t>(window.count()), -1);
  for (Index c = 0; c < model.mesh.num_cells(); ++c) {
    const auto ijk = layout.cell_ijk(c);
    const Index w = (ijk[0] - window.lo[0]) +
                    window.size[0] * ((ijk[1] - window.lo[1]) + window.size[1] * (ijk[2] - window.lo[2]));
    node_of_cell[static_cast<std::size_t>(w)] = model.dofmap.cell_nodes(c)[0];
  }
  casefile::CaseConfig short_config = config;
  short_config.nonlocal.horizon =
      config.solver.preconditioner_horizon * layout.spacing.head(config.dim()).maxCoeff();
  const assembly::StructuredNonlocalOperator short_K(grid_offset_blocks(short_config, layout), layout.cells,
                                                     window, node_of_cell);
  std::shared_ptr<const la::Distribution> distribution;
  std::vector<char> owned_cells;
  if (la::world_size() > 1) {
    distribution = distribution_over_processes(model);
    owned_cells.resize(node_of_cell.size());
    for (std::size_t c = 0; c < node_of_cell.size(); ++c)
      owned_cells[c] = node_of_cell[c] >= 0 && distribution->owns(node_of_cell[c]);
  }
  // Each process builds and inserts the rows of its own cells only.
  la::Matrix P =
      distribution ? la::Matrix(short_K.sparsity(owned_cells), distribution) : la::Matrix(short_K.sparsity());
  short_K.assemble(P, owned_cells);
  P.finalize();
  return {assembly::StructuredNonlocalOperator(grid_offset_blocks(config, layout), layout.cells, window,
                                               std::move(node_of_cell)),
          std::move(P), std::move(owned_cells)};
}

}  // namespace perimorph::system
