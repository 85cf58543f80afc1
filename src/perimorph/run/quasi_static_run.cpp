#include "perimorph/run/quasi_static_run.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/checkpoint.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace perimorph::run {

QuasiStaticRun::QuasiStaticRun(const setup::Discretization& disc, const RunOptions& options)
    : disc_(&disc),
      start_(std::chrono::steady_clock::now()),
      state_(disc),
      u_(disc.dofmap.num_dofs(), disc.dim()),
      internal_(disc.dofmap.num_dofs(), disc.dim()) {
  const auto& config = disc.config;
  if (!options.progress)
    own_progress_ = std::make_unique<io::ProgressLine>(increments(), !options.quiet, start_);
  progress_ = options.progress ? options.progress : own_progress_.get();
  la::add_options(config.solver.petsc_options);

  checkpoint_every_ =
      options.checkpoint_every >= 0 ? options.checkpoint_every : config.output.checkpoint_every;
  summary_.output_directory = resolve_output_directory(config, options);
  checkpoint_path_ = checkpoint_path(summary_.output_directory, basename_of(config));
  if (!options.restart.empty()) {
    restore(find_checkpoint(options.restart, basename_of(config)), options);
  } else {
    progress_->phase("loads");
    setup_ = prepare_run(disc);
    find_components();

    if (config.solver.op == casefile::SolverOperator::matrix_free) {
      progress_->phase("matrix-free operator");
      system_ = std::make_unique<system::ConstrainedSystem>(disc, system::build_matrix_free_stiffness(disc),
                                                            std::move(setup_.bc), setup_.F);
    } else {
      progress_->phase("assembly");
      system::AssembledStiffness assembled = system::assemble_stiffness_over_processes(disc);
      progress_->phase("solver set-up");
      system_ = std::make_unique<system::ConstrainedSystem>(disc, std::move(assembled.K),
                                                            std::move(setup_.bc), setup_.F);
    }
    // Laid out as the system (spread over the processes with it).
    u_ = system_->make_vector();
    internal_ = system_->make_vector();
    for (const auto& s : setup_.sets) summary_.reaction_names.push_back(s.name);
    output_ = std::make_unique<RunOutput>(disc, summary_.output_directory, basename_of(config),
                                          summary_.reaction_names);
  }
  system_->attach_solver();
  std::vector<double>().swap(setup_.F);  // the system holds the applied force
  choose_gather();
  if (options.restart.empty()) {
    u_prev_.assign(owned_dofs_.size(), 0.0);
    fint_prev_.assign(owned_dofs_.size(), 0.0);
  } else {  // restore() read them whole
    u_prev_ = owned_dofs_.of(u_prev_);
    fint_prev_ = owned_dofs_.of(fint_prev_);
  }
  summary_.csv_path = output_->csv_path();
  summary_.pvd_path = config.output.vtu ? output_->pvd_path() : "";
  progress_->start_increments();
}

void QuasiStaticRun::find_components() {
  for (auto& c : setup_.components)
    if (auto* f = dynamic_cast<evolution::BondFailure*>(c.get()))
      fracture_ = f;
    else if (auto* a = dynamic_cast<evolution::Adaptivity*>(c.get()))
      adaptivity_ = a;
    else if (auto* d = dynamic_cast<evolution::LocalDamage*>(c.get()))
      damage_ = d;
}

QuasiStaticRun::~QuasiStaticRun() = default;

void QuasiStaticRun::apply_load(int i) {
  state_.increment = i + 1;
  state_.load_factor = disc_->config.loading.factors[static_cast<std::size_t>(i)];
  rec_ = IncrementRecord{};
  damage_updates_ = 0;
  newton_steps_before_ = damage_ ? damage_->newton_steps() : 0;
  failed_before_ = bonds_failed();
  dissipated_before_ = state_.energy.dissipated;
}

void QuasiStaticRun::solve() {
  stop_if_asked();
  const double lambda = state_.load_factor;
  try {
    // Failed bonds can leave mechanisms no support finds: a direct solve that
    // holds null pivots may then take over (la::LinearSolver).
    if (bonds_failed() > 0) system_->allow_direct_fallback();
    summary_.last_solve = system_->solve(lambda, u_);
    summary_.preconditioner_rebuilds += summary_.last_solve.rebuilt_preconditioner ? 1 : 0;
    if (summary_.last_solve.direct_fallback) {
      ++summary_.direct_fallback_solves;
      summary_.most_null_pivots = std::max(summary_.most_null_pivots, summary_.last_solve.null_pivots);
    }
  } catch (const SolverError& e) {
    progress_->finish();
    const std::size_t failed = bonds_failed();
    throw SolverError(fmt::format(
        "increment {}/{} (load factor {}): {}{}\n{}", state_.increment, increments(), lambda, e.what(),
        failed > 0 ? fmt::format(". {} bonds have failed: they can leave a mechanism, e.g. a part held only "
                                 "by bonds normal to its motion (parts cut free completely and motions "
                                 "inside one cell are held automatically, CSV columns floating_parts "
                                 "and cell_mechanisms)",
                                 failed)
                   : "",
        kept()));
  }
  warn_unused_options();
  const auto solved = std::chrono::steady_clock::now();
  const double iteration_seconds = std::chrono::duration<double>(solved - last_solved_).count();
  last_solved_ = solved;
  double& work = state_.energy.external_work;
  if (rec_.break_iterations == 0) {
    // Work of all external forces (applied + reactions = K u at equilibrium)
    // on the elastic step from the last state.
    system_->apply_K(u_, internal_);
    state_.u = gather(u_);
    fint_ = owned(internal_);
    work = add_over_dofs(work, [&](std::size_t j) {
      const auto k = static_cast<std::size_t>(owned_dofs_.dof(j));
      return 0.5 * (fint_[j] + fint_prev_[j]) * (state_.u[k] - u_prev_[j]);
    });
    return;
  }
  // A re-equilibration at fixed load.
  const std::vector<double> u_before = owned_dofs_.of(state_.u);
  if (fracture_ && bonds_failed_in_pass_ && fracture_->applied_energy().count > 0) {
    const evolution::FailureEnergy& failed = fracture_->applied_energy();
    output_->add_failure_row(state_.increment, rec_.break_iterations, failed.count, failed,
                             failed.max_stretch / fracture_->s_crit(), summary_.last_solve,
                             iteration_seconds);
  }
  state_.u = gather(u_);
  const std::vector<double>& F = system_->applied_force();  // at the owned dofs
  work = add_over_dofs(work, [&](std::size_t j) {
    const auto k = static_cast<std::size_t>(owned_dofs_.dof(j));
    return lambda * F[j] * (state_.u[k] - u_before[j]);
  });
}

void QuasiStaticRun::warn_unused_options() {
  // The solver has read its options (the preconditioner's at its first set-up).
  if (options_checked_) return;
  options_checked_ = true;
  auto unused = la::unused_options();
  // The damage's Newton solver (-damage_ options) reads its options at its
  // first solve, which may come later.
  if (disc_->config.damage.solver == casefile::DamageSolver::newton)
    std::erase_if(unused, [](const std::string& o) { return o.starts_with("-damage_"); });
  if (!unused.empty())
    progress_->message(
        fmt::format("warning: PETSc did not use the option(s) {}: misspelt, or meant for a solver or "
                    "preconditioner not in use (the case's [solver] petsc_options and the command line; "
                    "-help lists the options the solver reads)",
                    fmt::join(unused, ", ")));
}

bool QuasiStaticRun::evolve() {
  bool changed = false, damage_changed = false;
  bonds_failed_in_pass_ = false;
  for (auto& component : setup_.components) {
    if (damage_changed && component.get() == fracture_) continue;
    evolution::Proposal proposal;
    try {
      proposal = component->inspect(state_, *system_);
    } catch (const Error& e) {  // e.g. a part cut free with unbalanced loads (part_support.hpp)
      stop_unsupported(e);
    }
    if (proposal.quiet()) continue;
    if (component.get() == damage_) {
      // The fixed point restarts after every change of the model by bond
      // failure or α: the cap is on consecutive damage updates.
      if (damage_updates_ == disc_->config.damage.max_iterations) stop_damage_unsettled();
      ++damage_updates_;
      ++rec_.damage_iterations;
      damage_changed = true;
    } else if (component.get() != adaptivity_) {
      damage_updates_ = 0;
    }
    if (!changed) {
      if (rec_.break_iterations == disc_->config.fracture.max_iterations) stop_unsettled(proposal.changes);
      ++rec_.break_iterations;
    }
    changed = true;
    const evolution::Effect effect = component->apply(state_, *system_);
    if (component.get() == fracture_) bonds_failed_in_pass_ = true;
    if (effect == evolution::Effect::rebuild) {
      damage_updates_ = 0;
      // A new model: re-solve before any other component looks at the state.
      rebuild();
      return true;
    }
  }
  if (!changed) return false;
  system_->operator_changed();
  if (bonds_failed_in_pass_ && disc_->config.output.failed_bonds) {
    std::vector<assembly::StretchedBond> bonds;
    std::vector<evolution::BondPoints> points;
    fracture_->proposed_on_process_zero(bonds, points);  // collective
    output_->add_failed_bonds(state_.increment, rec_.break_iterations, bonds, points, fracture_->s_crit());
  }
  return true;
}

void QuasiStaticRun::record(bool force_vtu) {
  const double lambda = state_.load_factor;
  const std::vector<double>& uv = state_.u;
  const std::vector<double>& F = system_->applied_force();
  if ((fracture_ || damage_) && rec_.break_iterations > 0) {
    system_->apply_K(u_, internal_);
    fint_ = owned(internal_);
  }
  if (damage_) {
    const evolution::EnergyLedger& e = state_.energy;
    rec_.damage_dissipated = e.damage_dissipated;
    rec_.damage_newton_steps = damage_->newton_steps() - newton_steps_before_;
    rec_.overshoot = e.overshoot;
    const auto& dm = *disc_->damage;
    const int npts = dm.points_per_cell;
    rec_.damaged_points = rec_.critical_points = 0;
    rec_.max_damage = 0.0;
    // On a piece of the model, each process counts the cells of its part.
    const auto* piece = disc_->piece.get();
    for (Index c = 0; c < disc_->mesh.num_cells(); ++c) {
      const int law = dm.law_of(c);
      if (law < 0 || (piece && !piece->of_part(c))) continue;
      for (int q = 0; q < npts; ++q) {
        const double d = setup::DamageModel::at(state_.history, c, q, npts);
        rec_.damaged_points += d > 0.0;
        rec_.critical_points += d >= dm.laws[static_cast<std::size_t>(law)].d_c;
        rec_.max_damage = std::max(rec_.max_damage, d);
      }
    }
    if (piece) {
      const std::vector<double> counts = la::sum_over_processes(
          {static_cast<double>(rec_.damaged_points), static_cast<double>(rec_.critical_points)});
      rec_.damaged_points = static_cast<std::size_t>(counts[0]);
      rec_.critical_points = static_cast<std::size_t>(counts[1]);
      const std::vector<double> largest = la::all_gather({rec_.max_damage});
      rec_.max_damage = *std::max_element(largest.begin(), largest.end());
    }
  }
  if (fracture_) {
    rec_.bonds_broken = bonds_failed();
    rec_.dissipated = state_.energy.dissipated;
    rec_.overshoot = state_.energy.overshoot;
    const evolution::CrackArea crack = fracture_->crack_area(state_);
    rec_.crack_area = crack.projected;
    rec_.broken_face_area = crack.total;
    rec_.floating_parts = state_.floating_parts;
    rec_.cell_mechanisms = state_.cell_mechanisms;
  }
  if (adaptivity_) {
    const auto& nl = *disc_->nonlocal;
    // On a piece, counted over its part's cells and summed over the processes.
    double dg = 0.0, nonlocal = 0.0;
    for (Index c = 0; c < disc_->mesh.num_cells(); ++c) {
      if (disc_->piece && !disc_->piece->of_part(c)) continue;
      dg += disc_->dofmap.continuity(c) != dofs::Continuity::continuous ? 1.0 : 0.0;
      nonlocal += nl.points.cell_alpha_max[static_cast<std::size_t>(c)] > 0.0 ? 1.0 : 0.0;
    }
    const std::vector<double> counts =
        disc_->piece ? la::sum_over_processes({static_cast<double>(owned_dofs_.size()), dg, nonlocal})
                     : std::vector<double>{static_cast<double>(disc_->dofmap.num_dofs()), dg, nonlocal};
    rec_.dofs = static_cast<Index>(counts[0]);
    rec_.dg_cells = static_cast<Index>(counts[1]);
    rec_.nonlocal_cells = static_cast<Index>(counts[2]);
    rec_.alpha_balls = adaptivity_->balls().size();
    rec_.model_change = state_.energy.model_change;
    rec_.remodel_seconds = remodel_seconds_;
    output_->add_alpha_balls(std::span(adaptivity_->balls()).subspan(balls_written_));
    balls_written_ = adaptivity_->balls().size();
  }
  std::vector<double> reaction(fint_);
  for (std::size_t j = 0; j < reaction.size(); ++j) reaction[j] -= lambda * F[j];
  const double energy = add_over_dofs(
      0.0, [&](std::size_t j) { return 0.5 * uv[static_cast<std::size_t>(owned_dofs_.dof(j))] * fint_[j]; });
  u_prev_ = owned_dofs_.of(uv);
  fint_prev_ = fint_;
  state_.energy.strain_energy = energy;

  const double work = state_.energy.external_work;
  rec_.increment = state_.increment;
  rec_.load_factor = lambda;
  rec_.reactions = reactions(reaction);
  rec_.strain_energy = energy;
  rec_.external_work = work;
  rec_.iterations = summary_.last_solve.iterations;
  rec_.relative_residual = summary_.last_solve.relative_residual;
  rec_.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  rec_.released = fracture_ || damage_ ? state_.energy.released() : 0.0;
  // The VTU first, then the row and its PVD entry (RunOutput::add_row): the
  // files stay in step whatever fails.
  const int i = state_.increment;
  if (force_vtu || i % disc_->config.output.every == 0 || i == increments()) write_vtu(i, true);
  output_->add_row(rec_);
  summary_.reactions = rec_.reactions;
  summary_.strain_energy = energy;
  summary_.external_work = work;
  summary_.history.push_back(rec_);
  stop_if_not_finite();
}

void QuasiStaticRun::write_vtu(int increment, bool listed_by_row) {
  if (!output_->writes_vtu()) return;
  // Collective on several processes: each writes its piece (RunOutput).
  const std::span<const Index> cells = output_->cells_written(*disc_);
  output_->write_increment_vtu(*disc_, cells, increment, state_.load_factor, state_.u,
                               fracture_ ? fracture_->fields(state_, cells) : evolution::FractureFields{},
                               damage_ ? damage_->fields(state_, cells) : evolution::DamageFields{},
                               listed_by_row);
}

void QuasiStaticRun::write_increment() {
  if (adaptivity_) adaptivity_->join_silent(state_);
  if (fracture_) {
    rec_.bonds_broken_increment = bonds_failed() - failed_before_;
    rec_.dissipated_increment = state_.energy.dissipated - dissipated_before_;
  }
  record(false);
  summary_.increments_done = state_.increment;
  progress_->update(
      state_.increment,
      damage_     ? fmt::format("{} its, {} damage iterations, max d {:.3g}{}", rec_.iterations,
                                rec_.damage_iterations, rec_.max_damage,
                            fracture_ ? fmt::format(", {} bonds failed", rec_.bonds_broken_increment) : "")
      : fracture_ ? fmt::format("{} its, {} bonds failed ({} iterations)", rec_.iterations,
                                rec_.bonds_broken_increment, rec_.break_iterations)
                  : fmt::format("{} its, residual {:.1e}", rec_.iterations, rec_.relative_residual));
}

RunSummary QuasiStaticRun::finish() {
  progress_->finish();
  // On a piece of the model u stays the piece's: nothing as long as the whole model.
  summary_.displacement = disc_->piece ? state_.u : whole(state_.u);
  summary_.dofs =
      halo_ ? static_cast<Index>(la::sum_over_processes({static_cast<double>(owned_dofs_.size())})[0])
            : disc_->dofmap.num_dofs();
  summary_.alpha = state_.alpha;
  summary_.damage = state_.history;
  if (disc_->piece && disc_->nonlocal) {
    summary_.failed_bond_points = evolution::failed_bond_points_over_processes(*disc_, state_);  // collective
  } else if (disc_->nonlocal) {
    const auto& pts = disc_->nonlocal->points;
    for (const auto& id : state_.failed_in_order)
      summary_.failed_bond_points.emplace_back(bonds::point_position(disc_->mesh, pts, id.e, id.g),
                                               bonds::point_position(disc_->mesh, pts, id.f, id.h));
  }
  return std::move(summary_);
}

}  // namespace perimorph::run
