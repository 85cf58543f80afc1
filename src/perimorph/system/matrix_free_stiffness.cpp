#include "perimorph/system/matrix_free_stiffness.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/system/stiffness.hpp"

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
  std::vector<Index> node_of_cell(static_cast<std::size_t>(model.mesh.num_cells()));
  for (Index c = 0; c < model.mesh.num_cells(); ++c)
    node_of_cell[static_cast<std::size_t>(c)] = model.dofmap.cell_nodes(c)[0];
  casefile::CaseConfig short_config = config;
  short_config.nonlocal.horizon =
      config.solver.preconditioner_horizon * layout.spacing.head(config.dim()).maxCoeff();
  const assembly::StructuredNonlocalOperator short_K(grid_offset_blocks(short_config, layout), layout.cells,
                                                     node_of_cell);
  std::shared_ptr<const la::Distribution> distribution;
  std::vector<char> owned_cells;
  if (la::world_size() > 1) {
    distribution = distribution_over_processes(model);
    owned_cells.resize(node_of_cell.size());
    for (std::size_t c = 0; c < node_of_cell.size(); ++c)
      owned_cells[c] = distribution->owns(node_of_cell[c]);
  }
  // Each process builds and inserts the rows of its own cells only.
  la::Matrix P =
      distribution ? la::Matrix(short_K.sparsity(owned_cells), distribution) : la::Matrix(short_K.sparsity());
  short_K.assemble(P, owned_cells);
  P.finalize();
  return {assembly::StructuredNonlocalOperator(grid_offset_blocks(config, layout), layout.cells,
                                               std::move(node_of_cell)),
          std::move(P), std::move(owned_cells)};
}

}  // namespace perimorph::system
