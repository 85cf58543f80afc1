#include "perimorph/evolution/bond_failure.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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
  holders_ = CellHolders(disc, decides_);  // collective on several processes
}

assembly::NonlocalSpace BondFailure::space(const RunState& state) const {
  return disc_->nonlocal_space(&state.failed);
}

Proposal BondFailure::inspect(const RunState& state, const system::ConstrainedSystem& /*system*/) {
  proposed_ = select(state, &proposed_points_);
  if (decides_.empty()) return {proposed_.size()};
  return {static_cast<std::size_t>(la::sum_over_processes({static_cast<double>(proposed_.size())})[0])};
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
  if (points != nullptr) {
    const auto& pts = disc_->nonlocal->points;
    where.reserve(over.size());
    for (const auto& b : over)
      where.push_back({bonds::point_position(disc_->mesh, pts, b.id.e, b.id.g),
                       bonds::point_position(disc_->mesh, pts, b.id.f, b.id.h)});
  }
  if (spec.rule == casefile::BreakRule::fraction) {
    double smax = 0.0;
    for (const auto& b : over) smax = std::max(smax, b.stretch);
    if (!decides_.empty()) smax = la::largest_over_processes(smax);  // collective
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
  // Each bond to the processes holding its cell e; the pass's totals and
  // places from the per-cell summary (bond_decisions.hpp).
  const SharedPass pass = share_pass(*disc_, bonds, s_crit_, holders_, !decides_.empty());
  std::vector<double> block;
  BondShape bs;
  for (std::size_t k = 0; k < pass.bonds.size(); ++k) {
    assembly::StretchedBond b = pass.bonds[k].bond;
    const double critical = pass.bonds[k].critical;
    b.id.e = setup::local_cell(*disc_, b.id.e);
    b.id.f = setup::local_cell(*disc_, b.id.f);
    if (b.id.e < 0 || b.id.f < 0) continue;  // a piece holding e but not f: no row of its
    if (!state.failed.add(b.id)) continue;
    state.failed_in_order.push_back(b.id);
    if (disc_->piece) state.failed_place.push_back(state.failed_over_model + pass.place[k]);
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
  state.failed_over_model += pass.count;
  const FailureEnergy energy{pass.dissipated, pass.overshoot, pass.count, pass.max_stretch};
  state.energy.dissipated += energy.dissipated;
  state.energy.overshoot += energy.overshoot;
  return energy;
}

void BondFailure::proposed_on_process_zero(std::vector<assembly::StretchedBond>& bonds,
                                           std::vector<BondPoints>& points) const {
  bonds = proposed_;
  points = proposed_points_;
  gather_pass_on_process_zero(*disc_, bonds, points, !decides_.empty());
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
  // The broken faces of this process's cells e: per normal axis, how many
  // and their columns (the other two cell indices of the box).
  std::array<double, 3> faces{};
  std::array<std::set<std::array<Index, 2>>, 3> columns;
  std::vector<assembly::InterfaceBonds> mine = assembly::interface_bonds(space(state), decides_);
  for (const auto& i : mine) {
    if (i.total == 0 || i.failed < i.total) continue;
    const auto a = static_cast<std::size_t>(i.axis);
    faces[a] += 1.0;
    const auto ijk = layout.cell_ijk(i.e);
    std::array<Index, 2> key{};
    for (int d = 0, k = 0; d < 3; ++d)
      if (d != i.axis) key[static_cast<std::size_t>(k++)] = ijk[static_cast<std::size_t>(d)];
    columns[a].insert(key);
  }
  std::array<double, 3> distinct{};
  for (std::size_t a = 0; a < 3; ++a) distinct[a] = static_cast<double>(columns[a].size());
  if (!decides_.empty()) {
    // Each column counted by one process (la::hashed_process), whichever
    // processes' cells have faces in it; the counts summed (whole numbers: exact).
    const int processes = la::world_size(), rank = la::world_rank();
    std::array<std::set<std::array<Index, 2>>, 3> counted;
    std::vector<la::Parcel> sent;
    for (int axis = 0; axis < 3; ++axis)
      for (const auto& key : columns[static_cast<std::size_t>(axis)]) {
        const int p = la::hashed_process({key[0], key[1], axis}, processes);
        if (p == rank) {
          counted[static_cast<std::size_t>(axis)].insert(key);
          continue;
        }
        std::vector<double>& to = la::parcel_for(sent, p);
        to.insert(to.end(),
                  {static_cast<double>(axis), static_cast<double>(key[0]), static_cast<double>(key[1])});
      }
    for (const la::Parcel& p : la::exchange(sent))
      for (std::size_t k = 0; k < p.values.size(); k += 3)
        counted[static_cast<std::size_t>(p.values[k])].insert(
            {static_cast<Index>(p.values[k + 1]), static_cast<Index>(p.values[k + 2])});
    const std::vector<double> sums = la::sum_over_processes(
        {faces[0], faces[1], faces[2], static_cast<double>(counted[0].size()),
         static_cast<double>(counted[1].size()), static_cast<double>(counted[2].size())});
    std::copy_n(sums.begin(), 3, faces.begin());
    std::copy_n(sums.begin() + 3, 3, distinct.begin());
  }
  for (int axis = 0; axis < dim; ++axis) {
    const auto a = static_cast<std::size_t>(axis);
    out.total += faces[a] * face_area(axis);
    out.projected = std::max(out.projected, distinct[a] * face_area(axis));
  }
  return out;
}

}  // namespace perimorph::evolution
