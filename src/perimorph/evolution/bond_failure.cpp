#include "perimorph/evolution/bond_failure.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/setup/critical_stretch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace perimorph::evolution {

BondFailure::BondFailure(const setup::Discretization& model)
    : model_(model),
      s_crit_(setup::critical_stretch(model)),
      broken_(model.mesh.num_cells(), model.nonlocal->points.per_cell),
      cell_dissipated_(static_cast<std::size_t>(model.mesh.num_cells()), 0.0) {
  const auto& regions = model.config.fracture.no_fail;
  if (!regions.empty()) no_fail_.assign(static_cast<std::size_t>(model.mesh.num_cells()), 0);
  for (const std::string& region : regions)
    for (Index c : model.mesh.cell_sets.at(region)) no_fail_[static_cast<std::size_t>(c)] = 1;
}

assembly::NonlocalSpace BondFailure::space() const {
  const auto& nl = *model_.nonlocal;
  assembly::NonlocalSpace s{model_.mesh, model_.dofmap, nl.points, nl.graph, nl.kernel};
  s.broken = &broken_;
  return s;
}

std::vector<assembly::StretchedBond> BondFailure::select(std::span<const double> u) const {
  std::vector<assembly::StretchedBond> over = assembly::bonds_over(space(), u, s_crit_);
  const auto& spec = model_.config.fracture;
  std::erase_if(over, [&](const assembly::StretchedBond& b) {
    if (!spec.intra_cell_failure && b.id.e == b.id.f) return true;
    return !no_fail_.empty() &&
           (no_fail_[static_cast<std::size_t>(b.id.e)] || no_fail_[static_cast<std::size_t>(b.id.f)]);
  });
  if (spec.rule == casefile::BreakRule::fraction && !over.empty()) {
    double smax = 0.0;
    for (const auto& b : over) smax = std::max(smax, b.stretch);
    const double bar = spec.fraction * smax;
    std::erase_if(over, [&](const assembly::StretchedBond& b) { return b.stretch < bar; });
  }
  return over;
}

FailureEnergy BondFailure::apply(const std::vector<assembly::StretchedBond>& bonds,
                                 system::ConstrainedSystem& system) {
  const int dim = model_.dim();
  const auto& pts = model_.nonlocal->points;
  const auto& dm = model_.dofmap;
  const std::vector<double>& applied_force = system.applied_force();
  const std::vector<double> ones{1.0};
  std::vector<double> block;
  std::vector<Index> dofs;
  FailureEnergy energy;
  for (const auto& b : bonds) {
    if (!broken_.add(b.id)) continue;
    const double critical = assembly::energy_at_stretch(b, s_crit_);
    energy.dissipated += critical;
    energy.overshoot += b.energy - critical;
    cell_dissipated_[static_cast<std::size_t>(b.id.e)] += 0.5 * critical;
    cell_dissipated_[static_cast<std::size_t>(b.id.f)] += 0.5 * critical;
    const auto nodes_e = dm.cell_nodes(b.id.e), nodes_f = dm.cell_nodes(b.id.f);
    const bool same = b.id.e == b.id.f;
    const int nE = static_cast<int>(nodes_e.size()), nF = static_cast<int>(nodes_f.size());
    const double* Ng = nE == 1 ? ones.data() : pts.shape.data() + b.id.g * nE;
    const double* Nh = nF == 1 ? ones.data() : pts.shape.data() + b.id.h * nF;
    dofs.clear();
    for (Index node : nodes_e)
      for (int d = 0; d < dim; ++d) dofs.push_back(node * dim + d);
    if (!same)
      for (Index node : nodes_f)
        for (int d = 0; d < dim; ++d) dofs.push_back(node * dim + d);
    const std::size_t m = dofs.size();
    block.assign(m * m, 0.0);
    dispatch_dim(
        dim, [&](auto D) { peridynamics::bond_block<D()>(Ng, nE, Nh, nF, same, b.xi, b.k, block.data()); });
    system.downdate(dofs, block);
  }
  // A free dof whose every bond has failed has a zero row: the matrix turns
  // singular. Such a dof is coupled to nothing, so holding it at zero by a
  // spring of its initial stiffness changes no other dof.
  const std::vector<Index> detached = system.without_stiffness(system.finish_downdate());
  for (Index d : detached) {
    const double force = applied_force[static_cast<std::size_t>(d)];
    if (force != 0.0) {
      const Vec3 x = dm.node_coordinate(d / dim);
      throw Error(
          fmt::format("bond failures have left the node at ({:g}, {:g}, {:g}) with no stiffness in "
                      "direction {} while an applied force {:g} acts on it: there is no quasi-static "
                      "equilibrium",
                      x.x(), x.y(), x.z(), "xyz"[d % dim], force));
    }
  }
  system.hold(detached, true);
  detached_ += detached.size();
  held_.insert(held_.end(), detached.begin(), detached.end());
  // A cell pair that lost its last intact bond may have cut a part free
  // (floating_parts.hpp): hold its free rigid-body modes by springs on a
  // minimal set of its dofs, which carry no force.
  // (select returns the bonds grouped by cell pair: each pair is looked at once.)
  const auto sp = space();
  bool separated = false;
  for (std::size_t k = 0; k < bonds.size() && !separated; ++k) {
    const auto& id = bonds[k].id;
    if (k > 0 && bonds[k - 1].id.e == id.e && bonds[k - 1].id.f == id.f) continue;
    separated = !assembly::has_intact_bond(sp, id.e, id.f);
  }
  if (separated) {
    std::vector<Index> held = held_;
    const auto& prescribed = system.bc().dofs;
    held.insert(held.end(), prescribed.begin(), prescribed.end());
    std::sort(held.begin(), held.end());
    const FloatingParts parts = find_floating_parts(model_, sp, held, applied_force);
    system.hold(parts.pins, false);
    held_.insert(held_.end(), parts.pins.begin(), parts.pins.end());
    floating_parts_ += static_cast<std::size_t>(parts.parts);
  }
  system.operator_changed();
  energy_.dissipated += energy.dissipated;
  energy_.overshoot += energy.overshoot;
  return energy;
}

FractureFields BondFailure::fields() const {
  FractureFields out;
  out.dissipated = cell_dissipated_;
  const auto w = assembly::point_bond_weights(space());
  const auto& pts = model_.nonlocal->points;
  out.damage.assign(cell_dissipated_.size(), 0.0);
  for (Index c = 0; c < model_.mesh.num_cells(); ++c) {
    double d = 0.0;
    for (int q = 0; q < pts.per_cell; ++q) {
      const std::size_t k = pts.index(c, q);
      d += w.total[k] > 0.0 ? w.lost[k] / w.total[k] : 0.0;
    }
    out.damage[static_cast<std::size_t>(c)] = d / pts.per_cell;
  }
  return out;
}

CrackArea BondFailure::crack_area() const {
  CrackArea out;
  if (!model_.mesh.structure) {
    out.total = out.projected = std::nan("");
    return out;
  }
  const auto& layout = *model_.mesh.structure;
  const Vec3& h = layout.spacing;
  const int dim = model_.dim();
  auto face_area = [&](int axis) {
    double a = model_.scale;  // thickness (2D), cross-section (1D), 1 (3D)
    for (int d = 0; d < dim; ++d)
      if (d != axis) a *= h[d];
    return a;
  };
  // Per normal axis, the positions (the other two cell indices) of the broken faces.
  std::array<std::set<std::array<Index, 2>>, 3> columns;
  for (const auto& i : assembly::interface_bonds(space())) {
    if (i.total == 0 || i.failed < i.total) continue;
    out.total += face_area(i.axis);
    const auto ijk = layout.cell_ijk(i.e);
    std::array<Index, 2> key{};
    for (int d = 0, k = 0; d < 3; ++d)
      if (d != i.axis) key[static_cast<std::size_t>(k++)] = ijk[static_cast<std::size_t>(d)];
    columns[static_cast<std::size_t>(i.axis)].insert(key);
  }
  for (int axis = 0; axis < dim; ++axis)
    out.projected = std::max(
        out.projected, static_cast<double>(columns[static_cast<std::size_t>(axis)].size()) * face_area(axis));
  return out;
}

}  // namespace perimorph::evolution
