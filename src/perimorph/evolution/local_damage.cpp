#include "perimorph/evolution/local_damage.hpp"

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/damage_newton.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <array>
#include <numeric>

namespace perimorph::evolution {

namespace {

/// Subtracts each (square, symmetric) block from the system: K −= block.
class DowndateInserter final : public assembly::MatrixInserter {
 public:
  explicit DowndateInserter(system::ConstrainedSystem& system) : system_(system) {}
  void add(std::span<const Index> rows, std::span<const Index> /*cols*/,
           std::span<const double> values) override {
    system_.downdate(rows, values);
  }

 private:
  system::ConstrainedSystem& system_;  ///< non-owning
};

}  // namespace

namespace {

/// ½ uᵀ K u − λ Fᵀ u (K the system's unconstrained stiffness, F the applied
/// force at load factor 1). `u` needs to be exact at the dofs this process
/// owns only (collective).
double potential(const system::ConstrainedSystem& system, std::span<const double> u, double lambda) {
  la::Vector x = system.make_vector(), Kx = system.make_vector();
  x.assign_replicated(u);
  system.K().mult(x, Kx);
  const la::OwnedDofs& owned = system.owned_dofs();
  const auto k = Kx.at_owned(owned);
  const auto& F = system.applied_force();  // at the owned dofs
  PERIMORPH_ASSERT(F.size() == owned.size(), "the system's owned dofs are the vector's");
  return owned.sum(0.0, [&](std::size_t j) {
    const auto i = static_cast<std::size_t>(owned.dof(j));
    return 0.5 * u[i] * k[j] - lambda * F[j] * u[i];
  });
}

}  // namespace

void LocalDamage::ledger_move(RunState& state, const system::ConstrainedSystem& system,
                              std::span<const double> u_newton) const {
  state.energy.overshoot -=
      potential(system, u_newton, state.load_factor) - potential(system, state.u, state.load_factor);
}

LocalDamage::LocalDamage(const setup::Discretization& disc)
    : disc_(&disc),
      tolerance_(disc.config.damage.tolerance),
      newton_(disc.config.damage.solver == casefile::DamageSolver::newton),
      decides_(setup::cells_of_process(disc, la::world_size(), la::world_rank())),
      holders_(disc, decides_) {
  PERIMORPH_ASSERT(disc.damage.has_value(), "LocalDamage needs a damage model");
}

void LocalDamage::rebind(const setup::Discretization& disc, RunState& /*state*/,
                         system::ConstrainedSystem& /*system*/) {
  disc_ = &disc;
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());  // a new piece: new cells
  holders_ = CellHolders(disc, decides_);
}

Proposal LocalDamage::inspect(const RunState& state, const system::ConstrainedSystem& /*system*/) {
  const setup::DamageModel& dm = *disc_->damage;
  const Index ncells = disc_->mesh.num_cells();
  const int npts = dm.points_per_cell;
  const int nv = fem::voigt_size(disc_->dim());
  const assembly::LocalSpace space = disc_->local_space();
  // Each cell's points are independent: computed in parallel, gathered in
  // cell order (the same proposal for any thread count).
  std::vector<std::vector<DamageChange>> per_cell(static_cast<std::size_t>(ncells));
#pragma omp parallel
  {
    std::vector<double> strain(static_cast<std::size_t>(npts * nv)), volume(static_cast<std::size_t>(npts));
#pragma omp for schedule(static)
    for (Index c = 0; c < ncells; ++c) {
      const int law = dm.law_of(c);
      if (law < 0 || !disc_->has_local_stiffness(c)) continue;
      if (!decides_.empty() && decides_[static_cast<std::size_t>(c)] == 0) continue;  // another process's
      const fem::DamageLaw& L = dm.laws[static_cast<std::size_t>(law)];
      const double* C0 = dm.C0[static_cast<std::size_t>(law)].data();
      assembly::strains_at_points(space, c, state.u, strain, volume);
      const auto whole_cell = static_cast<std::size_t>(setup::global_cell(*disc_, c));
      for (int q = 0; q < npts; ++q) {
        const auto n = static_cast<std::size_t>(npts), p = static_cast<std::size_t>(q);
        const std::size_t k = static_cast<std::size_t>(c) * n + p;
        const double Y = fem::damage_force(C0, strain.data() + q * nv, nv);
        const double old = state.history[k];
        const double d = fem::updated_damage(L, Y, old);
        if (d <= old) continue;
        const double w = volume[p];
        const double dissipated = (fem::damage_dissipation(L, d) - fem::damage_dissipation(L, old)) * w;
        per_cell[static_cast<std::size_t>(c)].push_back({k, whole_cell * n + p, d, old, Y, w, dissipated});
      }
    }
  }
  std::vector<DamageChange> mine;
  for (auto& changes : per_cell) mine.insert(mine.end(), changes.begin(), changes.end());
  proposed_ = share_damage(*disc_, mine, npts, holders_, !decides_.empty());
  largest_ = proposed_.largest;
  if (largest_ <= tolerance_) proposed_ = {};
  return {proposed_.count};
}

Effect LocalDamage::apply(RunState& state, system::ConstrainedSystem& system) {
  if (newton_ && state.increment != newton_failed_in_) {
    std::vector<double> u = state.u;
    const DamageNewtonReport rep = solve_damage_newton(*disc_, system, state.history, state.load_factor, u);
    newton_steps_ += rep.steps;
    if (rep.converged) {
      // Newton moved u at the old stiffness without the load moving: the
      // stored energy changed by ½(u_Nᵀ K u_N − u₀ᵀ K u₀) less the work of the
      // applied forces. The update below books what the stiffness drop
      // releases at u_N; what the move stored is taken from it, so that the
      // ledger stays W = U + D + D_d + overshoot + released.
      ledger_move(state, system, u);
      state.u = std::move(u);
      inspect(state, system);  // the update goes to Newton's d
    } else {
      ++newton_failures_;
      newton_failed_in_ = state.increment;  // the fixed point finishes this increment
    }
  }
  const setup::DamageModel& dm = *disc_->damage;
  const int npts = dm.points_per_cell;
  const int dim = disc_->dim();
  const int nv = fem::voigt_size(dim);
  // Δd C₀ at the changed points (0 elsewhere) of the changed cells.
  fem::ConstitutiveField delta(dim, disc_->mesh.num_cells(), npts);
  const int zero = delta.add_tensor(Eigen::MatrixXd::Zero(nv, nv));
  for (Index c = 0; c < disc_->mesh.num_cells(); ++c) delta.set_cell(c, zero);
  std::vector<char> changed(static_cast<std::size_t>(disc_->mesh.num_cells()), 0);
  std::vector<Eigen::MatrixXd> C(static_cast<std::size_t>(npts));
  const auto n = static_cast<std::size_t>(npts);
  // At fixed u, the stiffness drop releases Y Δd per volume; what the
  // threshold does not dissipate is the overshoot of the finite step (≥ 0).
  // Booked over the model (on a piece, the cells it lacks too).
  state.energy.damage_dissipated += proposed_.dissipated;
  state.energy.overshoot += proposed_.overshoot;
  const std::vector<DamageChange>& held = proposed_.held;
  for (std::size_t first = 0; first < held.size();) {
    const auto c = static_cast<Index>(held[first].point / n);
    const Eigen::MatrixXd& C0 = dm.C0[static_cast<std::size_t>(dm.law_of(c))];
    for (auto& m : C) m = Eigen::MatrixXd::Zero(nv, nv);
    std::size_t last = first;
    for (; last < held.size() && held[last].point / n == static_cast<std::size_t>(c); ++last) {
      const DamageChange& ch = held[last];
      C[ch.point % n] = (ch.d - ch.old) * C0;
      state.history[ch.point] = ch.d;
    }
    delta.set_cell_points(c, C);
    changed[static_cast<std::size_t>(c)] = 1;
    first = last;
  }
  DowndateInserter downdate(system);
  assembly::assemble_elasticity(disc_->local_space(), delta, downdate,
                                [&](Index c) { return changed[static_cast<std::size_t>(c)] != 0; });
  system.finish_downdate();
  return Effect::downdate;
}

DamageFields LocalDamage::fields(const RunState& state, std::span<const Index> cells) const {
  const setup::DamageModel& dm = *disc_->damage;
  std::vector<Index> every;
  if (cells.empty()) {
    every.resize(static_cast<std::size_t>(disc_->mesh.num_cells()));
    std::iota(every.begin(), every.end(), Index{0});
    cells = every;
  }
  const int npts = dm.points_per_cell;
  const int nv = fem::voigt_size(disc_->dim());
  DamageFields out;
  out.history = state.history;
  out.mean.assign(cells.size(), 0.0);
  out.max.assign(cells.size(), 0.0);
  out.dissipated.assign(cells.size(), 0.0);
  const assembly::LocalSpace space = disc_->local_space();
  std::vector<double> strain(static_cast<std::size_t>(npts * nv)), volume(static_cast<std::size_t>(npts));
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const Index c = cells[k];
    const int law = dm.law_of(c);
    if (law < 0) continue;
    bool any = false;
    for (int q = 0; q < npts; ++q) any = any || setup::DamageModel::at(state.history, c, q, npts) > 0.0;
    if (!any) continue;
    assembly::strains_at_points(space, c, state.u, strain, volume);
    double vol = 0.0;
    for (int q = 0; q < npts; ++q) {
      const double d = setup::DamageModel::at(state.history, c, q, npts);
      const double w = volume[static_cast<std::size_t>(q)];
      vol += w;
      out.mean[k] += d * w;
      out.max[k] = std::max(out.max[k], d);
      out.dissipated[k] += fem::damage_dissipation(dm.laws[static_cast<std::size_t>(law)], d) * w;
    }
    out.mean[k] /= vol;
  }
  return out;
}

}  // namespace perimorph::evolution
