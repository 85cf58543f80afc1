// The grid of an increment's VTU (RunOutput::increment_grid): the cells
// written (every cell, or a process's piece), the points they use, the
// displacement and α at the points, the strains, stresses and the fracture and
// damage fields of the cells.

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/morphed_stiffness.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/io/grid.hpp"
#include "perimorph/run/run_output.hpp"
#include "perimorph/setup/damage_model.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace perimorph::run {

namespace {

/// Voigt (engineering shear) to a row-major 3×3 tensor; `engineering` halves shears.
std::array<double, 9> voigt_to_tensor(const double* v, int dim, bool engineering) {
  const double h = engineering ? 0.5 : 1.0;
  std::array<double, 9> t{};
  if (dim == 1) {
    t[0] = v[0];
  } else if (dim == 2) {
    t[0] = v[0];
    t[4] = v[1];
    t[1] = t[3] = h * v[2];
  } else {
    t[0] = v[0];
    t[4] = v[1];
    t[8] = v[2];
    t[5] = t[7] = h * v[3];
    t[2] = t[6] = h * v[4];
    t[1] = t[3] = h * v[5];
  }
  return t;
}

io::VtkCell vtk_cell(int dim) {
  return dim == 1 ? io::VtkCell::line : dim == 2 ? io::VtkCell::quad : io::VtkCell::hexahedron;
}

}  // namespace

io::UnstructuredGrid RunOutput::increment_grid(const setup::Discretization& model, std::span<const double> u,
                                               const evolution::FractureFields& fracture,
                                               const evolution::DamageFields& damage,
                                               std::span<const Index> listed) const {
  const auto& dm = model.dofmap;
  const bool selected = !listed.empty();
  std::vector<Index> every;
  if (!selected) {
    every.resize(static_cast<std::size_t>(dm.num_cells()));
    std::iota(every.begin(), every.end(), Index{0});
  }
  const std::span<const Index> cells = selected ? listed : std::span<const Index>(every);
  for (Index c : cells)  // their stresses need their C
    PERIMORPH_ASSERT(model.computed_cells.empty() || model.computed_cells[static_cast<std::size_t>(c)],
                     "the output writes a cell whose morphed C this process did not compute");
  io::UnstructuredGrid grid;
  grid.nodes_per_cell = model.mesh.nodes_per_cell();
  grid.cell_type = vtk_cell(dim_);
  // Points are the dof nodes of the cells written, ascending: for the whole
  // model every dof node (point n is node n), for a piece its cells' nodes,
  // found by search (no array as long as the model's). A DG degree 0 cell is
  // drawn with its own corner points, all carrying its centroid node's displacement.
  std::vector<Index> point_dof_node;
  if (!selected) {
    point_dof_node.resize(static_cast<std::size_t>(dm.num_nodes()));
    std::iota(point_dof_node.begin(), point_dof_node.end(), Index{0});
  } else {
    point_dof_node = dm.dof_nodes_of_cells(cells);
  }
  const auto node_points = static_cast<std::ptrdiff_t>(point_dof_node.size());
  auto point_of_node = [&](Index n) {
    if (!selected) return n;
    const auto first = point_dof_node.begin();
    return static_cast<Index>(std::lower_bound(first, first + node_points, n) - first);
  };
  for (Index n : point_dof_node) grid.points.push_back(dm.node_coordinate(model.mesh, n));
  for (Index c : cells) {
    const auto nodes = dm.cell_nodes(c);
    if (static_cast<int>(nodes.size()) == grid.nodes_per_cell) {
      for (Index n : nodes) grid.connectivity.push_back(point_of_node(n));
      continue;
    }
    for (Index corner : model.mesh.cell(c)) {
      grid.connectivity.push_back(static_cast<Index>(grid.points.size()));
      grid.points.push_back(model.mesh.node(corner));
      point_dof_node.push_back(nodes[0]);
    }
  }

  io::Field disp{"displacement", 3, std::vector<double>(grid.points.size() * 3, 0.0)};
  for (std::size_t p = 0; p < grid.points.size(); ++p)
    for (int d = 0; d < dim_; ++d)
      disp.values[p * 3 + static_cast<std::size_t>(d)] =
          u[static_cast<std::size_t>(point_dof_node[p] * dim_ + d)];
  grid.point_data.push_back(std::move(disp));
  if (model.nonlocal) {
    io::Field alpha{"alpha", 1, {}};
    for (const Vec3& x : grid.points) alpha.values.push_back(model.nonlocal->alpha(x));
    grid.point_data.push_back(std::move(alpha));
  }

  // The stress of the damaged stiffness (THEORY §6) where the damage has grown.
  const fem::ConstitutiveField damaged =
      model.damage && !damage.history.empty()
          ? setup::damaged_stiffness(model.stiffness, *model.damage, damage.history)
          : fem::ConstitutiveField(0, 0, 0);
  const auto fields = assembly::cell_strain_stress(
      model.local_space(), damage.history.empty() ? model.stiffness : damaged, u, listed);
  const int nv = fem::voigt_size(dim_);
  io::Field strain{"strain", 9, {}}, stress{"stress", 9, {}}, region{"region", 1, {}},
      energy{"strain_energy_density", 1, {}};
  for (std::size_t k = 0; k < cells.size(); ++k) {  // the fields are in the order of `cells`
    const auto e = voigt_to_tensor(&fields.strain[k * static_cast<std::size_t>(nv)], dim_, true);
    const auto s = voigt_to_tensor(&fields.stress[k * static_cast<std::size_t>(nv)], dim_, false);
    strain.values.insert(strain.values.end(), e.begin(), e.end());
    stress.values.insert(stress.values.end(), s.begin(), s.end());
    region.values.push_back(model.mesh.cell_region[static_cast<std::size_t>(cells[k])]);
    energy.values.push_back(fields.energy_density[k]);
  }
  grid.cell_data = {std::move(strain), std::move(stress), std::move(region), std::move(energy)};
  if (model.nonlocal) {
    // α at the local quadrature points (cell mean) and the element kind:
    // 0 local/morphing (CG), 1 purely non-local CG, 2 DG, 3 DG degree 0.
    const auto& nl = *model.nonlocal;
    const std::size_t nq = model.rule.size();
    io::Field alpha_cell{"alpha_mean", 1, {}}, kind{"element_kind", 1, {}};
    for (Index c : cells) {
      double a = 0.0;
      for (std::size_t q = 0; q < nq; ++q)
        a += assembly::alpha_at_local_point(model.mesh, nl.alpha, c, model.rule[q].xi);
      alpha_cell.values.push_back(a / static_cast<double>(nq));
      const auto k = dm.continuity(c);
      kind.values.push_back(k == dofs::Continuity::discontinuous                    ? 2.0
                            : k == dofs::Continuity::discontinuous_constant         ? 3.0
                            : nl.morph.purely_nonlocal[static_cast<std::size_t>(c)] ? 1.0
                                                                                    : 0.0);
    }
    grid.cell_data.push_back(std::move(alpha_cell));
    grid.cell_data.push_back(std::move(kind));
  }
  auto cell_field = [&](const char* name, const std::vector<double>& values) {  // in the order of `cells`
    PERIMORPH_ASSERT(values.size() == cells.size(), "a cell field of another length than the cells written");
    grid.cell_data.push_back(io::Field{name, 1, values});
  };
  if (!fracture.damage.empty()) cell_field("damage", fracture.damage);
  if (!fracture.dissipated.empty()) cell_field("dissipated_energy", fracture.dissipated);
  if (!damage.mean.empty()) {
    cell_field("local_damage", damage.mean);
    cell_field("local_damage_max", damage.max);
    cell_field("damage_dissipated_energy", damage.dissipated);
  }
  if (selected) {
    // A piece: each cell's number in the whole mesh.
    io::Field number{"cell", 1, {}};
    for (Index c : cells)
      number.values.push_back(
          static_cast<double>(model.piece ? model.piece->global_cell[static_cast<std::size_t>(c)] : c));
    grid.cell_data.push_back(std::move(number));
  }
  return grid;
}

}  // namespace perimorph::run
