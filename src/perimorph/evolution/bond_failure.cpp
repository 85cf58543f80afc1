#include "perimorph/evolution/bond_failure.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>

namespace perimorph::evolution {

BondFailure::BondFailure(const setup::Discretization& disc) : s_crit_(setup::critical_stretch(disc)) {
  bind(disc);
}

void BondFailure::bind(const setup::Discretization& disc) {
  disc_ = &disc;
  const auto& regions = disc.config.fracture.no_fail;
  no_fail_.clear();
  if (!regions.empty()) no_fail_.assign(static_cast<std::size_t>(disc.mesh.num_cells()), 0);
  for (const std::string& region : regions)
    for (Index c : disc.mesh.cell_sets.at(region)) no_fail_[static_cast<std::size_t>(c)] = 1;
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());
}

namespace {

constexpr std::size_t kPacked = 16;  ///< doubles per bond in gather_bonds

/// Every process's bonds (each in cell order e, from disjoint sets of cells
/// e) and their points on every process, in whole-mesh cell order: the
/// one-process order. Sent in whole-mesh cell numbers, given back in the
/// model's (on a piece, e = f = -1 for a bond whose cells it does not both hold).
void gather_bonds(const setup::Discretization& disc, std::vector<assembly::StretchedBond>& bonds,
                  std::vector<BondPoints>& points) {
  std::vector<double> packed;
  packed.reserve(bonds.size() * kPacked);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const auto& b = bonds[k];
    const auto& p = points[k];
    packed.insert(packed.end(),
                  {static_cast<double>(setup::global_cell(disc, b.id.e)),
                   static_cast<double>(setup::global_cell(disc, b.id.f)), static_cast<double>(b.id.g),
                   static_cast<double>(b.id.h), b.stretch, b.energy, b.k, b.xi.x(), b.xi.y(), b.xi.z(),
                   p.g.x(), p.g.y(), p.g.z(), p.h.x(), p.h.y(), p.h.z()});
  }
  const std::vector<double> all = la::all_gather(packed);
  const std::size_t n = all.size() / kPacked;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return all[a * kPacked] < all[b * kPacked]; });
  bonds.assign(n, {});
  points.assign(n, {});
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = all.data() + order[i] * kPacked;
    auto& b = bonds[i];
    Index e = setup::local_cell(disc, static_cast<Index>(v[0])),
          f = setup::local_cell(disc, static_cast<Index>(v[1]));
    if (e < 0 || f < 0) e = f = -1;
    b.id = {e, f, static_cast<int>(v[2]), static_cast<int>(v[3])};
    b.stretch = v[4];
    b.energy = v[5];
    b.k = v[6];
    b.xi = Vec3(v[7], v[8], v[9]);
    points[i] = {Vec3(v[10], v[11], v[12]), Vec3(v[13], v[14], v[15])};
  }
}

}  // namespace

assembly::NonlocalSpace BondFailure::space(const RunState& state) const {
  return disc_->nonlocal_space(&state.failed);
}

Proposal BondFailure::inspect(const RunState& state, const system::ConstrainedSystem& /*system*/) {
  proposed_ = select(state, &proposed_points_);
  return {proposed_.size()};
}

Effect BondFailure::apply(RunState& state, system::ConstrainedSystem& system) {
  applied_ = apply(proposed_, state, system);
  return Effect::downdate;
}

std::vector<assembly::StretchedBond> BondFailure::select(const RunState& state,
                                                         std::vector<BondPoints>* points) const {
  std::vector<assembly::StretchedBond> over = assembly::bonds_over(space(state), state.u, s_crit_, decides_);
  const auto& spec = disc_->config.fracture;
  const setup::DamageModel* damage = disc_->damage ? &*disc_->damage : nullptr;
  std::erase_if(over, [&](const assembly::StretchedBond& b) {
    if (!spec.intra_cell_failure && b.id.e == b.id.f) return true;
    // THEORY §6: a bond may fail only where the damage has reached d_c (both ends).
    if (damage &&
        !(damage->critical(state.history, b.id.e, b.id.g) && damage->critical(state.history, b.id.f, b.id.h)))
      return true;
    return !no_fail_.empty() &&
           (no_fail_[static_cast<std::size_t>(b.id.e)] || no_fail_[static_cast<std::size_t>(b.id.f)]);
  });
  std::vector<BondPoints> where;
  if (points != nullptr || !decides_.empty()) {
    const auto& pts = disc_->nonlocal->points;
    where.reserve(over.size());
    for (const auto& b : over)
      where.push_back({bonds::point_position(disc_->mesh, pts, b.id.e, b.id.g),
                       bonds::point_position(disc_->mesh, pts, b.id.f, b.id.h)});
  }
  if (!decides_.empty()) gather_bonds(*disc_, over, where);
  if (spec.rule == casefile::BreakRule::fraction && !over.empty()) {
    double smax = 0.0;
    for (const auto& b : over) smax = std::max(smax, b.stretch);
    const double bar = spec.fraction * smax;
    std::size_t kept = 0;
    for (std::size_t k = 0; k < over.size(); ++k) {
      if (over[k].stretch < bar) continue;
      over[kept] = over[k];
      if (!where.empty()) where[kept] = where[k];
      ++kept;
    }
    over.resize(kept);
    if (!where.empty()) where.resize(kept);
  }
  if (points != nullptr) *points = std::move(where);
  return over;
}

void BondFailure::shape_of(const assembly::StretchedBond& b, BondShape& out) const {
  static constexpr double kOne = 1.0;
  const int dim = disc_->dim();
  const auto& pts = disc_->nonlocal->points;
  const auto& dm = disc_->dofmap;
  const auto nodes_e = dm.cell_nodes(b.id.e), nodes_f = dm.cell_nodes(b.id.f);
  out.same_cell = b.id.e == b.id.f;
  out.nE = static_cast<int>(nodes_e.size());
  out.nF = static_cast<int>(nodes_f.size());
  out.Ng = out.nE == 1 ? &kOne : pts.shape.data() + b.id.g * out.nE;
  out.Nh = out.nF == 1 ? &kOne : pts.shape.data() + b.id.h * out.nF;
  out.dofs.clear();
  for (Index node : nodes_e)
    for (int d = 0; d < dim; ++d) out.dofs.push_back(node * dim + d);
  if (!out.same_cell)
    for (Index node : nodes_f)
      for (int d = 0; d < dim; ++d) out.dofs.push_back(node * dim + d);
}

FailureEnergy BondFailure::apply(const std::vector<assembly::StretchedBond>& bonds, RunState& state,
                                 system::ConstrainedSystem& system) const {
  const int dim = disc_->dim();
  std::vector<double> block;
  BondShape bs;
  FailureEnergy energy;
  for (const auto& b : bonds) {
    const double critical = assembly::energy_at_stretch(b, s_crit_);
    if (b.id.e < 0) {  // on a piece, a bond it does not hold: in the ledger and the count only
      energy.dissipated += critical;
      energy.overshoot += b.energy - critical;
      ++state.failed_over_model;
      continue;
    }
    if (!state.failed.add(b.id)) continue;
    state.failed_in_order.push_back(b.id);
    if (disc_->piece) state.failed_place.push_back(state.failed_over_model);
    ++state.failed_over_model;
    energy.dissipated += critical;
    energy.overshoot += b.energy - critical;
    state.cell_dissipated[b.id.e] += 0.5 * critical;
    state.cell_dissipated[b.id.f] += 0.5 * critical;
    shape_of(b, bs);
    const std::size_t m = bs.dofs.size();
    block.assign(m * m, 0.0);
    dispatch_dim(dim, [&](auto D) {
      peridynamics::bond_block<D()>(bs.Ng, bs.nE, bs.Nh, bs.nF, bs.same_cell, b.xi, b.k, block.data());
    });
    system.downdate(bs.dofs, block);
  }
  system.finish_downdate();
  state.energy.dissipated += energy.dissipated;
  state.energy.overshoot += energy.overshoot;
  return energy;
}

FractureFields BondFailure::fields(const RunState& state, std::span<const Index> cells) const {
  std::vector<Index> every;
  if (cells.empty()) {
    every.resize(static_cast<std::size_t>(disc_->mesh.num_cells()));
    std::iota(every.begin(), every.end(), Index{0});
    cells = every;
  }
  FractureFields out;
  out.dissipated.reserve(cells.size());
  for (Index c : cells) {
    const auto it = state.cell_dissipated.find(c);
    out.dissipated.push_back(it != state.cell_dissipated.end() ? it->second : 0.0);
  }
  // The damage index of the cells this process decides (their graph rows).
  std::vector<Index> decided;
  for (Index c : cells)
    if (decides_.empty() || decides_[static_cast<std::size_t>(c)]) decided.push_back(c);
  const std::vector<double> d = assembly::cell_damage(space(state), decided);
  out.damage.assign(cells.size(), std::nan(""));
  for (std::size_t k = 0, j = 0; k < cells.size(); ++k)
    if (decides_.empty() || decides_[static_cast<std::size_t>(cells[k])]) out.damage[k] = d[j++];
  return out;
}

std::vector<assembly::InterfaceBonds> BondFailure::broken_interfaces(const RunState& state) const {
  std::vector<assembly::InterfaceBonds> mine = assembly::interface_bonds(space(state), decides_);
  std::erase_if(mine, [](const auto& i) { return i.total == 0 || i.failed < i.total; });
  if (decides_.empty()) return mine;
  // Each process looked at the faces of its cells e: every process gets them
  // all, in cell order (each process's in cell order, from disjoint cells).
  // In whole-mesh numbers (a piece's box cells are its cells' whole numbers).
  std::vector<double> packed;
  for (const auto& i : mine)
    packed.insert(packed.end(),
                  {static_cast<double>(setup::global_cell(*disc_, i.e)),
                   static_cast<double>(setup::global_cell(*disc_, i.f)), static_cast<double>(i.axis)});
  const std::vector<double> all = la::all_gather(packed);
  std::vector<assembly::InterfaceBonds> out(all.size() / 3);
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k].e = static_cast<Index>(all[3 * k]);
    out[k].f = static_cast<Index>(all[3 * k + 1]);
    out[k].axis = static_cast<int>(all[3 * k + 2]);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.e < b.e; });
  return out;
}

CrackArea BondFailure::crack_area(const RunState& state) const {
  CrackArea out;
  if (!disc_->mesh.structure) {
    out.total = out.projected = std::nan("");
    return out;
  }
  const auto& layout = *disc_->mesh.structure;
  const Vec3& h = layout.spacing;
  const int dim = disc_->dim();
  auto face_area = [&](int axis) {
    double a = disc_->scale;  // thickness (2D), cross-section (1D), 1 (3D)
    for (int d = 0; d < dim; ++d)
      if (d != axis) a *= h[d];
    return a;
  };
  // Per normal axis, the positions (the other two cell indices) of the broken faces.
  std::array<std::set<std::array<Index, 2>>, 3> columns;
  for (const auto& i : broken_interfaces(state)) {
    out.total += face_area(i.axis);
    const auto ijk =
        decides_.empty() ? layout.cell_ijk(i.e) : layout.box_cell_ijk(i.e);  // whole-mesh numbers
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
