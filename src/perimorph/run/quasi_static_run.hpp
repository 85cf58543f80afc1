#pragma once
// The steps of a quasi-static run (THEORY §4–§6), so that run_static reads
// as the algorithm: apply the load; solve; let every evolution component
// inspect the state and apply its change, re-solving at fixed load until all
// are quiet; write the increment. A QuasiStaticRun owns the run's state
// (evolution/run_state.hpp), its constrained system, its components and its
// output; it keeps the energy ledger and reports errors with what is kept on
// disk.

#include "perimorph/evolution/adaptivity.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/local_damage.hpp"
#include "perimorph/evolution/run_state.hpp"
#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/owned_dofs.hpp"
#include "perimorph/run/run_output.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/system/constrained_system.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace perimorph::io {
class ProgressLine;
}

namespace perimorph::run {

/// The case's [output] basename, or its file's stem.
std::string basename_of(const casefile::CaseConfig& config);

class QuasiStaticRun {
 public:
  /// Constraints and loads first (a case error stops the run before the
  /// assembly), then K, the constrained system with its solver, the output.
  QuasiStaticRun(const setup::Discretization& disc, const RunOptions& options);
  ~QuasiStaticRun();

  int increments() const { return static_cast<int>(disc_->config.loading.factors.size()); }
  /// The first increment to compute (0-based): 0, or the one after a restored
  /// checkpoint's.
  int first_increment() const { return summary_.restarted_after; }
  /// Starts increment i (0-based) at its load factor.
  void apply_load(int i);
  /// Solves at the state's load factor and adds the work of the step to the
  /// ledger: the first solve of an increment is an elastic step (K fixed on
  /// it, the trapezoidal rule exact); a re-solve after components changed the
  /// model is at fixed load (prescribed dofs do not move, applied forces are
  /// constant: λ F·Δu exactly). Throws SolverError naming the increment.
  void solve();
  /// Every component in order: inspect, and apply its proposal unless quiet;
  /// then the solver takes the changed operator. False when all were quiet.
  /// While the damage changes, bond failure waits for the next pass (bonds
  /// fail irreversibly: they are judged on a damage-converged solution).
  /// With damage, damage still moving after [damage] max_iterations
  /// consecutive updates (no bond failure or growth of α in between) stops
  /// the run (Error) with its state written.
  /// With [fracture], an increment still changing after max_iterations passes
  /// stops the run (Error) with its state written.
  bool evolve();
  /// With [adaptivity] update = "increment" and redo: once the increment has
  /// settled, α grows from its failed bonds (THEORY §5); true if it grew: the
  /// increment goes on at the grown model (solve, evolve) and settles again.
  bool adapt();
  /// With [adaptivity] update = "increment" and redo = false: after the
  /// increment is written, α grows for the next one.
  void adapt_for_next();
  /// The increment's CSV row, its VTU (every [output] every, and the last),
  /// the progress line.
  void write_increment();
  /// Writes the checkpoint (run/checkpoint.hpp) after every [output]
  /// checkpoint_every increments; call it once the increment is written and α
  /// has grown for the next one.
  void checkpoint_if_due();
  RunSummary finish();

 private:
  /// The CSV row (and VTU when due or `force_vtu`) of the state reached.
  void record(bool force_vtu);
  /// A reaction or an energy of the increment just recorded that is NaN or
  /// Inf stops the run (SolverError naming the increment and the columns).
  void stop_if_not_finite();
  /// "Results of increments 1..N are in DIR" for messages (and the checkpoint, if any).
  std::string kept() const;
  /// Writes the checkpoint of the state (that of a completed increment) and
  /// remembers it (quasi_static_checkpoint.cpp).
  void save_checkpoint();
  /// The run as the checkpoint `path` holds it, onto the caller's `disc` (or
  /// one rebuilt for the checkpoint's α): state, components, system, output
  /// position. Throws InputError for a checkpoint of another case or version.
  void restore(const std::string& path, const RunOptions& options);
  [[noreturn]] void stop_unsettled(std::size_t over);
  /// The damage still moves after [damage] max_iterations updates.
  [[noreturn]] void stop_damage_unsettled();
  /// The VTU fields of the state's fracture and damage (empty where absent);
  /// with `listed_by_row` its PVD entry waits for the CSV row (RunOutput::add_row).
  void write_vtu(int increment, bool listed_by_row = false);
  /// A pending stop request (core/interrupt.hpp) ends the run here, between
  /// solves: Interrupted, naming the increment and what is written.
  void stop_if_asked();
  [[noreturn]] void stop_unsupported(const std::exception& e);
  /// Sets halo_ and owned_dofs_ for the current system (after it is built
  /// or restored).
  void choose_gather();
  /// v's entries at the nodes this process reads (halo_; collective), or
  /// on one process v.
  std::vector<double> gather(const la::Vector& v);
  /// v's entries at owned_dofs_ (in its order), or on one process v.
  std::vector<double> owned(const la::Vector& v) const;
  /// The whole vector of `v` (whole-length), which is exact at the dofs this
  /// process owns (collective): what a checkpoint and the summary hold.
  std::vector<double> whole(const std::vector<double>& v) const;
  /// The bonds failed in the whole model, the same on every process: the
  /// state's on one process or a part; on a piece, which holds only its own,
  /// the bond failure's count.
  std::size_t bonds_failed() const;
  /// init + Σ term(j) over owned_dofs_' entries j (every dof on one process,
  /// in dof order; spread over processes, each process's sum added in rank
  /// order; collective).
  double add_over_dofs(double init, const std::function<double(std::size_t)>& term) const;
  /// The reaction of each set of setup_.sets: Σ over its nodes of r (r at
  /// owned_dofs_; spread over processes, each process's sums added in rank
  /// order: collective).
  std::vector<Vec3> reactions(std::span<const double> r) const;
  /// ½ uᵀ K u of the current u (K u left in internal_; collective).
  double strain_energy();
  /// Finds the bond-failure, adaptivity and damage components among setup_'s.
  void find_components();
  void warn_unused_options();
  /// Lets the adaptivity component grow α now; true if it did (and the run
  /// moved to the grown model).
  bool grow_alpha();
  /// The run moves to the discretization of the state's α (grown): rebuilt,
  /// the system remodelled (system/remodel.hpp), u carried over, the
  /// components rebound, the strain-energy change booked in the ledger
  /// (quasi_static_adapt.cpp).
  void rebuild();
  /// On a piece: the state carried to `next` (the piece rebuilt for the
  /// state's α) and the system remodelled onto it (system::remodel_piece);
  /// returns u_prev_ carried to next's numbering (piece-length, at next's
  /// owned dofs), and leaves the state's u so (rebuild gathers its halo).
  std::vector<double> move_to_piece(const setup::Discretization& next);
  /// An array at the owned dofs (owned_dofs_ order) at every dof the process
  /// reads (gather; collective).
  std::vector<double> gather_owned(std::span<const double> owned_values);

  const setup::Discretization* disc_;             ///< the current one: the caller's (non-owning) or owned_
  std::unique_ptr<setup::Discretization> owned_;  ///< rebuilt for a grown α (null before)
  std::chrono::steady_clock::time_point start_;
  /// end of the last solve: a bond-breaking iteration (stretch pass, update, re-solve) is timed from it
  std::chrono::steady_clock::time_point last_solved_;
  std::unique_ptr<io::ProgressLine> own_progress_;
  io::ProgressLine* progress_ = nullptr;  ///< non-owning: own_progress_ or the caller's
  RunSetup setup_;
  std::unique_ptr<system::ConstrainedSystem> system_;
  evolution::BondFailure* fracture_ = nullptr;   ///< non-owning: the bond-failure component, if any
  evolution::Adaptivity* adaptivity_ = nullptr;  ///< non-owning: the adaptivity component, if any
  evolution::LocalDamage* damage_ = nullptr;     ///< non-owning: the damage component, if any
  int newton_steps_before_ = 0;                  ///< LocalDamage::newton_steps() when the increment began
  int damage_updates_ = 0;  ///< consecutive damage updates (no bond failed, α unchanged in between)
  bool bonds_failed_in_pass_ = false;  ///< the last evolve pass broke bonds (fracture_->proposed() is new)
  std::size_t balls_written_ = 0;      ///< adaptivity_->balls() already in the output
  double remodel_seconds_ = 0.0;       ///< spent in rebuild(), cumulative
  std::unique_ptr<RunOutput> output_;
  evolution::RunState state_;
  la::Vector u_, internal_;  ///< the solution (initial guess of the next solve), K u
  /// Spread over processes (empty on one): u is brought to each process at
  /// setup::nodes_read only, NaN elsewhere in state_.u.
  std::optional<la::NodeGather> halo_;
  /// The dofs this process owns (every dof on one process): K u and the last
  /// recorded state are read there only, and held there only (issue 17).
  la::OwnedDofs owned_dofs_;
  /// u and K u of the last recorded state, and K u of this one, at owned_dofs_.
  std::vector<double> u_prev_, fint_prev_, fint_;
  IncrementRecord rec_;  ///< of the increment in progress
  std::size_t failed_before_ = 0;
  double dissipated_before_ = 0.0;
  bool options_checked_ = false;
  int checkpoint_every_ = 0;
  std::string checkpoint_path_;  ///< where save_checkpoint writes
  RunSummary summary_;
};

}  // namespace perimorph::run
