#pragma once
// The adaptive non-local zone (THEORY §5, thesis §3.3.4, fig. 3.8), an
// evolution component (component.hpp): α grows with the crack. Every cell
// that holds a newly failed bond adds a ball (disk in 2D) centred on its
// centroid, α = 1 to radius h_e + core and falling to 0 at h_e + core +
// transition (h_e the longest side of the cell; with core ≥ δ every failed
// bond ends up at least δ inside α = 1); α never decreases. The predictor
// (beyond the thesis) adds the ball of a cell not yet at α = 1 whose strain
// stretches some direction beyond θ·s_crit, before any of its bonds fails, so
// that a crack may start where no non-local zone was placed. apply changes
// the state's α and returns Effect::rebuild: the run rebuilds the
// discretization and carries the system and the state over
// (setup::rebuild_for_alpha, system::remodel).

#include "perimorph/evolution/component.hpp"
#include "perimorph/setup/discretization.hpp"

#include <set>
#include <vector>

namespace perimorph::evolution {

/// One ball added to α, as the run's log and `BASENAME_alpha.csv` list it:
/// with the case's [[alpha.region]] entries these reproduce α at any increment.
struct AlphaBall {
  int increment = 0;  ///< the increment whose state added it
  Index cell = 0;     ///< the cell it is centred on
  Vec3 center = Vec3::Zero();
  double radius = 0.0;           ///< α = 1 inside
  double transition = 0.0;       ///< α falls to 0 over this width beyond the radius
  bool predicted = false;        ///< added by the predictor (no failed bond in the cell yet)
  bool critical_damage = false;  ///< added because the cell's damage reached d_c (THEORY §6)
};

class Adaptivity final : public Component {
 public:
  /// The case's [adaptivity]; `s_crit` for the predictor.
  Adaptivity(const setup::Discretization& disc, double s_crit);

  std::string_view name() const override { return "adaptive non-local zone"; }
  /// The cells to add a ball for, not seeded before: with the predictor,
  /// cells with α < 1 at a non-local point whose largest principal strain at
  /// a local quadrature point exceeds θ·s_crit; when growth is due (update =
  /// "iteration", or allow_growth() since the last apply), the cells of the
  /// bonds failed since the last growth and, with [material.damage], the
  /// cells with a local quadrature point at d = d_c (THEORY §6: α = 1 holds
  /// every point where the damage is critical). Balls that raise α at no non-local
  /// or local quadrature point are not proposed (a run whose α never grows
  /// equals the fixed run): they join α with the next apply or join_silent.
  /// With the predictor, throws Error if
  /// a bond failed in a cell whose α was below 1 (the predictor was late).
  Proposal inspect(const RunState& state, const system::ConstrainedSystem& system) override;
  /// Joins the proposed balls to the state's α; Effect::rebuild.
  Effect apply(RunState& state, system::ConstrainedSystem& system) override;
  void rebind(const setup::Discretization& disc, RunState& state, system::ConstrainedSystem& system) override;
  /// The balls, the seeded cells and how far the failed bonds were read
  /// (adaptivity.cpp).
  void save(core::BinaryWriter& out) const override;
  void restore(const setup::Discretization& disc, core::BinaryReader& in) override;

  /// Lets the next inspect (that one only) grow α from the failed bonds
  /// (update = "increment": the run calls it when an increment has settled).
  void allow_growth() { growth_due_ = true; }
  /// Joins to the state's α the balls inspect found to raise α at no
  /// quadrature point (the discretization stays the same: no rebuild); the
  /// run calls it when an increment ends, so that α holds every ball.
  void join_silent(RunState& state);
  /// Every ball added, in order.
  const std::vector<AlphaBall>& balls() const { return balls_; }

 private:
  /// A ball a process found, with its place in the order one process finds
  /// them (phase: 0 predictor, 1 critical damage, 2 failed bonds; order:
  /// the whole cell, or 2 × the bond's place in the order of failure + its end).
  struct Candidate {
    int phase = 0;
    double order = 0.0;
    AlphaBall ball;
  };
  /// Whether this process decides on local cell c (decides_), and whether
  /// the cell has its ball.
  bool decides(Index c) const;
  bool seeded(Index c) const;
  /// Appends the ball of local cell c (its whole number in AlphaBall::cell).
  void candidate(std::vector<Candidate>& out, int phase, double order, Index c, int increment, bool predicted,
                 bool critical_damage = false) const;
  /// Every process's candidates (collective where spread over processes), in order.
  std::vector<Candidate> gathered(std::vector<Candidate> mine, int increment) const;
  /// With the predictor, throws Error if a bond failed since the last check
  /// in a cell whose α was below 1 (collective on a piece: the first such
  /// bond in the order of failure is named on every process).
  void check_predictor_in_time(const RunState& state);
  /// Adds `balls` to the state's α and to balls_; empties it.
  void join(std::vector<AlphaBall>& balls, RunState& state);
  /// True if the ball raises α at some non-local or local quadrature point
  /// of a cell this process decides on (a ball inside α = 1 changes nothing,
  /// and is not applied; the processes' answers are joined in inspect).
  bool raises_alpha(const AlphaBall& b) const;

  const setup::Discretization* disc_;  ///< non-owning: the run's current discretization
  double s_crit_ = 0.0;
  double core_ = 0.0, transition_ = 0.0;
  bool growth_due_ = false;
  std::size_t seen_ = 0;     ///< failed bonds already grown from (RunState::failed_over_model)
  std::size_t checked_ = 0;  ///< failed bonds already checked against α (predictor)
  std::set<Index>
      seeded_;  ///< the cells (whole-mesh numbers) with a ball: those of balls_, silent_, proposed_
  /// The cells this process decides on (setup::cells_of_process: each cell by
  /// one process, the candidates gathered; empty: every cell).
  std::vector<char> decides_;
  std::vector<AlphaBall> proposed_, silent_, balls_;
};

}  // namespace perimorph::evolution
