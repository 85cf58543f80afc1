#pragma once
// Local damage (THEORY §6, thesis §3.4), an evolution component
// (component.hpp): after a solve, the damage at every local quadrature point
// of a damageable cell is updated from the strain (fem/damage_law.hpp), and
// the stiffness follows: K −= ∫ Bᵀ (Δd C₀) B over the points whose d grew
// (ConstrainedSystem::downdate), nothing reassembled. Solving again and
// updating again is the fixed-point (secant) iteration of the increment; it
// has converged when no point's d would change by more than the [damage]
// tolerance. While the damage is still moving, bond failure waits (the run's
// evolve: bonds, which fail irreversibly, are judged on a damage-converged
// solution; fig. 3.22 alternates the two).

#include "perimorph/evolution/component.hpp"
#include "perimorph/evolution/damage_decisions.hpp"
#include "perimorph/setup/discretization.hpp"

#include <span>
#include <vector>

namespace perimorph::evolution {

/// Per-cell damage fields for the VTU (empty for a run without damage), for
/// the cells it writes, in their order.
struct DamageFields {
  std::vector<double> mean;        ///< d, mean over the cell's local quadrature points
  std::vector<double> max;         ///< d, largest over them
  std::vector<double> dissipated;  ///< energy the damage dissipated in the cell (k0 d + ½ k1 d² per volume)
  std::span<const double> history;  ///< d at every local quadrature point (the stress is the damaged one)
};

class LocalDamage final : public Component {
 public:
  explicit LocalDamage(const setup::Discretization& disc);

  std::string_view name() const override { return "local damage"; }
  /// The points whose d grows at the state's displacement, proposed only when
  /// the largest growth exceeds the [damage] tolerance (else quiet: converged).
  Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) override;
  /// Raises d at the proposed points, downdates the system by Δd C₀ there,
  /// books the dissipation and the overshoot in the ledger. Effect::downdate.
  /// With [damage] solver = "newton", first moves the state's u to the
  /// solution of the increment's damage problem (evolution/damage_newton.hpp)
  /// and proposes again there; if Newton does not converge (12 steps, or
  /// the line search stalls at a kink of d(u) such as the cap at d_c), the
  /// secant update goes on from the last solve, for the rest of that
  /// increment (newton_failures counts it).
  Effect apply(RunState& state, system::ConstrainedSystem& system) override;
  void rebind(const setup::Discretization& disc, RunState& /*state*/,
              system::ConstrainedSystem& /*system*/) override;
  /// The Newton counters and the last change (local_damage_checkpoint.cpp).
  void save(core::BinaryWriter& out) const override;
  void restore(const setup::Discretization& disc, core::BinaryReader& in) override;

  /// Newton steps taken and Newton solves that did not converge, over the run.
  int newton_steps() const { return newton_steps_; }
  int newton_failures() const { return newton_failures_; }
  /// The largest growth of d the last inspect found (converged: ≤ tolerance).
  double largest_change() const { return largest_; }
  /// The damage fields of each of `cells` (in that order; every cell if empty).
  DamageFields fields(const RunState& state, std::span<const Index> cells = {}) const;

 private:
  void ledger_move(RunState& state, const system::ConstrainedSystem& system,
                   std::span<const double> u_newton) const;
  const setup::Discretization* disc_;  ///< non-owning: the run's current discretization
  double tolerance_ = 0.0;
  bool newton_ = false;
  int newton_steps_ = 0, newton_failures_ = 0;
  int newton_failed_in_ = -1;  ///< the increment where Newton last failed: not tried again there
  double largest_ = 0.0;
  /// The cells this process updates (1), empty on one process: on several,
  /// each process computes the strains of its own cells (partition::cells_of_part),
  /// so each point is looked at once, and sends the changes to the processes
  /// holding the cells (damage_decisions.hpp).
  std::vector<char> decides_;
  CellHolders holders_;
  SharedDamage proposed_;
};

}  // namespace perimorph::evolution
