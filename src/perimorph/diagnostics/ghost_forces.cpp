#include "perimorph/diagnostics/ghost_forces.hpp"

#include "perimorph/io/csv_table.hpp"
#include "perimorph/io/grid.hpp"
#include "perimorph/io/vtu_writer.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace perimorph::diagnostics {

GhostForces compute_ghost_forces(const setup::Discretization& model, const Mat3& strain) {
  const int dim = model.dim();
  const auto& dm = model.dofmap;
  const Index n = dm.num_dofs();
  std::vector<double> uv(static_cast<std::size_t>(n));
  for (Index a = 0; a < dm.num_nodes(); ++a) {
    const Vec3 ua = strain * dm.node_coordinate(model.mesh, a);
    for (int d = 0; d < dim; ++d) uv[static_cast<std::size_t>(a * dim + d)] = ua[d];
  }
  // Spread over the processes of a distributed run (owner computes), the
  // residual gathered on every process.
  auto assembled = system::assemble_stiffness_over_processes(model);
  la::Vector u = assembled.K.make_vector(), r = assembled.K.make_vector();
  u.assign_replicated(uv);
  assembled.K.mult(u, r);
  GhostForces g;
  g.residual = r.to_replicated();
  for (Index dof : setup::build_dirichlet(model).dofs) g.residual[static_cast<std::size_t>(dof)] = 0.0;

  // Nodal volumes: the load of a unit body force in each component.
  std::vector<double> lumped(static_cast<std::size_t>(n), 0.0);
  assembly::assemble_body_force(
      model.local_space(), [](const Vec3&) { return Vec3::Ones(); }, lumped);
  // DG degree 0 nodes: the cell volume (the body-force loop assumes Q1 cells).
  g.nodal_volume.assign(static_cast<std::size_t>(dm.num_nodes()), 0.0);
  for (Index a = 0; a < dm.num_nodes(); ++a)
    g.nodal_volume[static_cast<std::size_t>(a)] = lumped[static_cast<std::size_t>(a * dim)];
  g.density.resize(g.residual.size());
  for (std::size_t k = 0; k < g.residual.size(); ++k) {
    const double v = g.nodal_volume[k / static_cast<std::size_t>(dim)];
    g.density[k] = v > 0 ? g.residual[k] / v : 0.0;
    g.max_density = std::max(g.max_density, std::abs(g.density[k]));
  }
  return g;
}

std::string write_ghost_forces(const setup::Discretization& model, const GhostForces& g,
                               const std::string& directory, const std::string& basename) {
  const int dim = model.dim();
  const auto& dm = model.dofmap;
  std::filesystem::create_directories(directory);
  const std::string csv_path = (std::filesystem::path(directory) / (basename + "_ghost_forces.csv")).string();
  std::vector<std::string> cols{"node", "x", "y", "z", "nodal_volume", "alpha"};
  const char* axes = "xyz";
  for (int d = 0; d < dim; ++d) cols.push_back(fmt::format("residual_{}", axes[d]));
  for (int d = 0; d < dim; ++d) cols.push_back(fmt::format("density_{}", axes[d]));
  io::CsvTable csv(csv_path, cols);
  for (Index a = 0; a < dm.num_nodes(); ++a) {
    const Vec3 x = dm.node_coordinate(model.mesh, a);
    std::vector<double> row{static_cast<double>(a),
                            x.x(),
                            x.y(),
                            x.z(),
                            g.nodal_volume[static_cast<std::size_t>(a)],
                            model.nonlocal ? model.nonlocal->alpha(x) : 0.0};
    for (int d = 0; d < dim; ++d) row.push_back(g.residual[static_cast<std::size_t>(a * dim + d)]);
    for (int d = 0; d < dim; ++d) row.push_back(g.density[static_cast<std::size_t>(a * dim + d)]);
    csv.add_row(row);
  }
  io::UnstructuredGrid grid;
  grid.points = dm.node_coordinates(model.mesh);
  grid.nodes_per_cell = model.mesh.nodes_per_cell();
  grid.cell_type = dim == 1 ? io::VtkCell::line : dim == 2 ? io::VtkCell::quad : io::VtkCell::hexahedron;
  bool all_q1 = true;
  for (Index c = 0; c < dm.num_cells(); ++c) {
    const auto nodes = dm.cell_nodes(c);
    all_q1 = all_q1 && static_cast<int>(nodes.size()) == grid.nodes_per_cell;
    grid.connectivity.insert(grid.connectivity.end(), nodes.begin(), nodes.end());
  }
  if (all_q1) {
    io::Field res{"ghost_force", 3, std::vector<double>(grid.points.size() * 3, 0.0)};
    io::Field den{"ghost_force_density", 3, std::vector<double>(grid.points.size() * 3, 0.0)};
    for (Index a = 0; a < dm.num_nodes(); ++a)
      for (int d = 0; d < dim; ++d) {
        res.values[static_cast<std::size_t>(a * 3 + d)] = g.residual[static_cast<std::size_t>(a * dim + d)];
        den.values[static_cast<std::size_t>(a * 3 + d)] = g.density[static_cast<std::size_t>(a * dim + d)];
      }
    grid.point_data = {std::move(res), std::move(den)};
    io::write_vtu((std::filesystem::path(directory) / (basename + "_ghost_forces.vtu")).string(), grid);
  }
  return csv_path;
}

}  // namespace perimorph::diagnostics
