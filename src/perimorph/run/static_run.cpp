#include "perimorph/run/static_run.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/run_output.hpp"
#include "perimorph/system/stiffness.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>

namespace perimorph::run {

std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options) {
  if (!options.output_directory.empty()) return options.output_directory;
  const std::filesystem::path dir(config.output.directory);
  if (dir.is_absolute()) return dir.string();
  return (std::filesystem::path(config.path).parent_path() / dir).lexically_normal().string();
}

RunSetup prepare_run(const setup::Discretization& model) {
  RunSetup setup;
  setup.bc = setup::build_dirichlet(model);
  setup.F = setup::build_external_force(model);
  setup.sets = setup::reaction_sets(model);
  if (model.config.fracture.enabled) setup.failure.emplace(model);
  return setup;
}

namespace {

std::string basename_of(const casefile::CaseConfig& config) {
  if (!config.output.basename.empty()) return config.output.basename;
  return std::filesystem::path(config.path).stem().string();
}

std::vector<Vec3> sum_reactions(const std::vector<setup::ReactionSet>& sets, std::span<const double> r,
                                int dim) {
  std::vector<Vec3> out;
  for (const auto& s : sets) {
    Vec3 f = Vec3::Zero();
    for (Index n : s.dof_nodes)
      for (int d = 0; d < dim; ++d) f[d] += r[static_cast<std::size_t>(n * dim + d)];
    out.push_back(f);
  }
  return out;
}

/// "[fracture] max_iterations in case.toml (now 7)" or "(default 10000)".
std::string max_iterations_source(const casefile::FractureSpec& spec) {
  const bool given = spec.max_iterations != casefile::FractureSpec{}.max_iterations;
  return fmt::format("[fracture] max_iterations in {} ({} {})", spec.where.file, given ? "now" : "default",
                     spec.max_iterations);
}

}  // namespace

RunSummary run_static(const setup::Discretization& model, const RunOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto& config = model.config;
  const int dim = model.dim();
  const auto& factors = config.loading.factors;
  const int total = static_cast<int>(factors.size());
  std::unique_ptr<io::ProgressLine> own_progress;
  if (!options.progress) own_progress = std::make_unique<io::ProgressLine>(total, !options.quiet, start);
  io::ProgressLine& progress = options.progress ? *options.progress : *own_progress;
  la::add_options(config.solver.petsc_options);

  // Constraints and loads first: a case error stops the run before the assembly.
  progress.phase("loads");
  RunSetup setup = prepare_run(model);
  const std::vector<double>& F = setup.F;
  const auto& sets = setup.sets;
  std::optional<evolution::BondFailure>& failure = setup.failure;

  progress.phase("assembly");
  system::AssembledStiffness assembled = system::assemble_stiffness(model);
  const Index n = model.dofmap.num_dofs();

  progress.phase("solver set-up");
  system::ConstrainedSystem system(model, std::move(assembled.K), std::move(setup.bc), F);
  system.attach_solver();
  const la::Matrix& K = system.K();

  RunSummary summary;
  for (const auto& s : sets) summary.reaction_names.push_back(s.name);
  summary.output_directory = resolve_output_directory(config, options);
  RunOutput output(model, summary.output_directory, basename_of(config), summary.reaction_names);
  summary.csv_path = output.csv_path();
  summary.pvd_path = config.output.vtu ? output.pvd_path() : "";

  progress.start_increments();
  la::Vector u(n, dim), internal(n, dim);
  std::vector<double> u_prev(static_cast<std::size_t>(n), 0.0), fint_prev(static_cast<std::size_t>(n), 0.0);
  double work = 0.0;
  bool options_checked = false;

  for (int i = 0; i < total; ++i) {
    const double lambda = factors[static_cast<std::size_t>(i)];
    auto kept = [&](int done) {
      return done == 0 ? fmt::format("No increment completed (output directory {})", summary.output_directory)
                       : fmt::format("Results of increments 1..{} are in {}", done, summary.output_directory);
    };
    auto solve = [&]() {
      try {
        summary.last_solve = system.solve(lambda, u);
      } catch (const SolverError& e) {
        progress.finish();
        const bool after_failures = failure && !failure->broken().empty();
        throw SolverError(fmt::format(
            "increment {}/{} (load factor {}): {}{}\n{}", i + 1, total, lambda, e.what(),
            after_failures
                ? fmt::format(". {} bonds have failed: they can leave a mechanism, e.g. a part held only "
                              "by bonds normal to its motion (parts cut free completely are held "
                              "automatically, CSV column floating_parts)",
                              failure->broken().size())
                : "",
            kept(i)));
      }
      // The solver has read its options (the preconditioner's at its first set-up).
      if (!options_checked) {
        options_checked = true;
        if (const auto unused = la::unused_options(); !unused.empty())
          progress.message(fmt::format(
              "warning: PETSc did not use the option(s) {}: misspelt, or meant for a solver or "
              "preconditioner not in use (the case's [solver] petsc_options and the command line; -help "
              "lists the options the solver reads)",
              fmt::join(unused, ", ")));
      }
    };
    solve();
    // Work of all external forces (applied + reactions = K u at equilibrium)
    // on the elastic step from the last state: K is fixed on it, so the
    // trapezoidal rule is exact.
    K.mult(u, internal);
    std::vector<double> uv = u.to_std();
    std::vector<double> fint = internal.to_std();
    for (std::size_t k = 0; k < uv.size(); ++k) work += 0.5 * (fint[k] + fint_prev[k]) * (uv[k] - u_prev[k]);

    IncrementRecord rec;
    // The CSV row (and VTU) of the state reached: after the loop, or when it
    // stops at max_iterations (then always with its VTU).
    auto record = [&](bool force_vtu) {
      if (failure) {
        if (rec.break_iterations > 0) {
          K.mult(u, internal);
          fint = internal.to_std();
        }
        rec.bonds_broken = failure->broken().size();
        rec.dissipated = failure->dissipated();
        rec.overshoot = failure->overshoot();
        const evolution::CrackArea crack = failure->crack_area();
        rec.crack_area = crack.projected;
        rec.broken_face_area = crack.total;
        rec.floating_parts = failure->floating_parts();
      }
      std::vector<double> reaction(fint);
      for (std::size_t k = 0; k < reaction.size(); ++k) reaction[k] -= lambda * F[k];
      double energy = 0.0;
      for (std::size_t k = 0; k < uv.size(); ++k) energy += 0.5 * uv[k] * fint[k];
      u_prev = uv;
      fint_prev = fint;

      rec.increment = i + 1;
      rec.load_factor = lambda;
      rec.reactions = sum_reactions(sets, reaction, dim);
      rec.strain_energy = energy;
      rec.external_work = work;
      rec.iterations = summary.last_solve.iterations;
      rec.relative_residual = summary.last_solve.relative_residual;
      rec.wall_time = std::chrono::duration<double>(clock::now() - start).count();
      rec.released = failure ? work - energy - rec.dissipated - rec.overshoot : 0.0;
      output.add_row(rec);
      const int every = config.output.every;
      if (force_vtu || (i + 1) % every == 0 || i + 1 == total)
        output.write_increment_vtu(model, i + 1, lambda, uv,
                                   failure ? failure->fields() : evolution::FractureFields{});
      summary.displacement = uv;
      summary.reactions = rec.reactions;
      summary.strain_energy = energy;
      summary.external_work = work;
      summary.history.push_back(rec);
    };

    if (failure) {
      // Re-equilibration at fixed load: prescribed dofs do not move, applied
      // forces are constant, so the external work is λ F·Δu exactly.
      const std::size_t before = failure->broken().size();
      const double dissipated_before = failure->dissipated();
      for (;;) {
        const auto bonds = failure->select(uv);
        if (bonds.empty()) break;
        if (rec.break_iterations == config.fracture.max_iterations) {
          rec.bonds_broken_increment = failure->broken().size() - before;
          rec.dissipated_increment = failure->dissipated() - dissipated_before;
          record(true);
          progress.finish();
          const std::string files =
              output.writes_vtu()
                  ? fmt::format("{} and its row in {}", output.vtu_path(i + 1), output.csv_path())
                  : fmt::format("its row in {} ([output] vtu = false)", output.csv_path());
          throw Error(fmt::format(
              "increment {}/{} (load factor {}): bonds still fail after {} bond-breaking iterations: {} "
              "bonds "
              "failed in this increment and {} more are over the criterion now. The crack is running "
              "unstably at this load (or the iterations do not settle). Use smaller load increments or "
              "raise {}. The state after the last iteration is kept as increment {}: {}; every iteration "
              "is in {}. {}",
              i + 1, total, lambda, rec.break_iterations, rec.bonds_broken_increment, bonds.size(),
              max_iterations_source(config.fracture), i + 1, files, output.failures_csv_path(), kept(i)));
        }
        ++rec.break_iterations;
        double max_stretch = 0.0;
        for (const auto& b : bonds) max_stretch = std::max(max_stretch, b.stretch);
        evolution::FailureEnergy energy_failed;
        try {
          energy_failed = failure->apply(bonds, system);
        } catch (const Error& e) {  // a part cut free with unbalanced loads (floating_parts.hpp)
          progress.finish();
          output.write_increment_vtu(model, i + 1, lambda, uv, failure->fields());
          throw Error(fmt::format(
              "increment {}/{} (load factor {}), bond-breaking iteration {}: {}. The displacement "
              "before this iteration is written as increment {} ({}); {}",
              i + 1, total, lambda, rec.break_iterations, e.what(), i + 1,
              output.writes_vtu() ? output.vtu_path(i + 1) : "no VTU: [output] vtu = false", kept(i)));
        }
        output.add_failed_bonds(model, i + 1, rec.break_iterations, bonds, failure->s_crit());
        const std::vector<double> u_before = uv;
        solve();
        output.add_failure_row(i + 1, rec.break_iterations, bonds.size(), energy_failed,
                               max_stretch / failure->s_crit(), summary.last_solve.iterations);
        uv = u.to_std();
        for (std::size_t k = 0; k < uv.size(); ++k) work += lambda * F[k] * (uv[k] - u_before[k]);
      }
      rec.bonds_broken_increment = failure->broken().size() - before;
      rec.dissipated_increment = failure->dissipated() - dissipated_before;
    }
    record(false);
    summary.increments_done = i + 1;
    progress.update(i + 1,
                    failure ? fmt::format("{} its, {} bonds failed ({} iterations)", rec.iterations,
                                          rec.bonds_broken_increment, rec.break_iterations)
                            : fmt::format("{} its, residual {:.1e}", rec.iterations, rec.relative_residual));
  }
  progress.finish();
  return summary;
}

}  // namespace perimorph::run
