#pragma once
// The quasi-static run (THEORY §4–§6): for each increment of the load ramp,
// solve A u = λ rhs with the constraints eliminated, let the evolution
// components (bond failure, the support of parts cut free; later adaptive α
// and damage) change the model and re-solve until they are quiet, then report
// reactions, energies and fields. The steps are QuasiStaticRun's
// (quasi_static_run.hpp).

#include "perimorph/evolution/component.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/run/run_output.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/discretization.hpp"

#include <memory>
#include <string>
#include <vector>

namespace perimorph::io {
class ProgressLine;
}

namespace perimorph::run {

struct RunOptions {
  std::string output_directory;  ///< overrides the case's [output] directory if not empty
  bool quiet = false;            ///< no progress line
  /// The progress line to continue (the caller's, which showed the set-up
  /// before the run, so that its elapsed time counts from the program's
  /// start); null: the run draws its own (unless quiet). Warnings go to it.
  io::ProgressLine* progress = nullptr;
  /// Continue the run from this checkpoint (a BASENAME.checkpoint file, or the
  /// output directory holding it; run/checkpoint.hpp) instead of starting it.
  std::string restart = {};
  /// Overrides [output] checkpoint_every when ≥ 0.
  int checkpoint_every = -1;
};

/// What a run needs besides the stiffness, built from the case before any
/// assembly, so that a case error stops `run` early and `check` finds every
/// error `run` would find before solving: the constraints, the loads, the
/// reaction sets and the evolution components (with [fracture]: bond failure,
/// whose set-up checks the critical stretch and no_fail regions, and the
/// support of parts cut free). Throws InputError naming the case-file entry.
struct RunSetup {
  setup::DirichletData bc;
  std::vector<double> F;  ///< external force at load factor 1
  std::vector<setup::ReactionSet> sets;
  /// In the order the run asks them after each solve (evolution/component.hpp).
  std::vector<std::unique_ptr<evolution::Component>> components;
};
RunSetup prepare_run(const setup::Discretization& model);

struct RunSummary {
  int increments_done = 0;
  /// The increment a restarted run continued after (its checkpoint's); 0 for a fresh run.
  int restarted_after = 0;
  /// The last checkpoint written by this run ("" if none) and its increment.
  std::string checkpoint_path;
  int checkpoint_increment = 0;
  /// The last solution (dof vector): the whole model's, or on a process's
  /// piece of the model (setup::cut_to_piece) the piece's, in its numbers.
  std::vector<double> displacement;
  Index dofs = 0;  ///< of the whole model
  std::vector<std::string> reaction_names;
  std::vector<Vec3> reactions;  ///< last increment, per reaction set
  double strain_energy = 0.0;
  double external_work = 0.0;
  la::SolveReport last_solve;
  /// Solves that rebuilt the reused preconditioner (la::LinearSolver: it failed, or the iterations had
  /// grown).
  int preconditioner_rebuilds = 0;
  /// Solves made by the direct fallback that holds null pivots (la::LinearSolver::allow_direct_fallback,
  /// allowed once bonds have failed), and the most null pivots one of them held.
  int direct_fallback_solves = 0;
  int most_null_pivots = 0;
  std::vector<IncrementRecord> history;  ///< one record per completed increment (what the CSV holds)
  /// α of the model the run ended on (grown with [adaptivity]).
  alpha::AlphaField alpha = alpha::AlphaField::constant(0.0);
  /// d at every local quadrature point at the end (RunState::history; empty
  /// without [material.damage]).
  std::vector<double> damage;
  /// The two ends of every failed bond, in the order they failed.
  std::vector<std::pair<Vec3, Vec3>> failed_bond_points;
  std::string output_directory, csv_path, pvd_path;
};

/// This process's part of the case's model: build_discretization with one
/// part per process of PETSC_COMM_WORLD (the CG/DG flags shared by their
/// union over the processes); the whole model on one. `on_phase` hears each
/// set-up phase. Collective.
setup::Discretization process_part(const casefile::CaseConfig& config,
                                   const setup::PhaseCallback& on_phase = {});

/// The model this process runs: on several processes, its part cut to its
/// piece (setup::cut_to_piece), where nothing as long as the whole model
/// is kept after the set-up: its failed bonds, damage changes and what they
/// cut loose are shared in whole-mesh cell numbers and dof names, and a
/// checkpoint is written in the whole model's numbers (run::WholeState). With
/// [adaptivity], the part is kept as the piece's source, from which a rebuild
/// for a grown α cuts the next piece (setup::rebuild_piece_for_alpha); without,
/// it is dropped. The part is built on the process's window of the case's box
/// (setup::part_window, partition::GridBisection: no array as long as the
/// whole mesh) where the case allows it (setup::has_windows: a box without
/// holes or cuts), else on the whole mesh (process_part). On one process the
/// whole model. Collective.
setup::Discretization process_model(const casefile::CaseConfig& config,
                                    const setup::PhaseCallback& on_phase = {});

/// Output directory of a case: the override if given, else the case's
/// [output] directory resolved against the case file's folder.
std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options);

/// Runs every increment. PETSc options of the case are inserted first (the
/// command line keeps precedence); after the first solve, options that PETSc
/// did not use are reported as a warning (la::unused_options). On a solver
/// failure throws SolverError saying which increment failed; what was computed
/// before stays on disk. With [fracture], an increment that still breaks bonds
/// after max_iterations iterations stops the run (Error): its state after the
/// last iteration is written (CSV row and VTU) and the message names the files.
/// With options.restart, continues a checkpointed run of the same case from
/// the increment after its checkpoint (run/checkpoint.hpp).
RunSummary run_static(const setup::Discretization& model, const RunOptions& options);

}  // namespace perimorph::run
