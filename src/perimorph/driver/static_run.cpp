#include "perimorph/driver/static_run.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/driver/bond_failure.hpp"
#include "perimorph/driver/boundary_conditions.hpp"
#include "perimorph/driver/run_output.hpp"
#include "perimorph/driver/stiffness.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/matrix.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <optional>

namespace perimorph::driver {

std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options) {
  if (!options.output_directory.empty()) return options.output_directory;
  const std::filesystem::path dir(config.output.directory);
  if (dir.is_absolute()) return dir.string();
  return (std::filesystem::path(config.path).parent_path() / dir).lexically_normal().string();
}

namespace {

std::string basename_of(const casefile::CaseConfig& config) {
  if (!config.output.basename.empty()) return config.output.basename;
  return std::filesystem::path(config.path).stem().string();
}

std::vector<Vec3> sum_reactions(const std::vector<ReactionSet>& sets, std::span<const double> r, int dim) {
  std::vector<Vec3> out;
  for (const auto& s : sets) {
    Vec3 f = Vec3::Zero();
    for (Index n : s.dof_nodes)
      for (int d = 0; d < dim; ++d) f[d] += r[static_cast<std::size_t>(n * dim + d)];
    out.push_back(f);
  }
  return out;
}

}  // namespace

RunSummary run_static(const Model& model, const RunOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto& config = model.config;
  const int dim = model.dim();
  la::add_options(config.solver.petsc_options);

  // K (kept unconstrained for reactions and energies) and the constrained copy A.
  AssembledStiffness assembled = assemble_stiffness(model);
  la::Matrix& K = assembled.K;
  const DirichletData bc = build_dirichlet(model);
  const std::vector<double> F = build_external_force(model);
  const Index n = model.dofmap.num_dofs();

  // Unit-load right-hand side with the constraints eliminated: linear in the
  // load factor, so it is scaled per increment.
  la::Vector g(n, dim), rhs_unit(n, dim), f_unit(n, dim);
  {
    std::vector<double> gv(static_cast<std::size_t>(n), 0.0);
    for (std::size_t k = 0; k < bc.dofs.size(); ++k) gv[static_cast<std::size_t>(bc.dofs[k])] = bc.values[k];
    g.assign(gv);
  }
  f_unit.assign(F);
  rhs_unit.copy_from(f_unit);
  la::Matrix A = K.duplicate();
  A.eliminate_dirichlet(bc.dofs, g, rhs_unit);
  A.set_spd();
  la::LinearSolver solver(config.solver.rtol, config.solver.max_iterations);
  solver.set_operator(A, model.dofmap.node_coordinates(), dim);

  // Bond failure (THEORY §5): after each solve, break the bonds over the
  // criterion, update K, A and the right-hand side, re-solve; until none breaks.
  std::optional<BondFailure> failure;
  if (config.fracture.enabled) failure.emplace(model);

  const auto sets = reaction_sets(model);
  RunSummary summary;
  for (const auto& s : sets) summary.reaction_names.push_back(s.name);
  summary.output_directory = resolve_output_directory(config, options);
  RunOutput output(model, summary.output_directory, basename_of(config), summary.reaction_names);
  summary.csv_path = output.csv_path();
  summary.pvd_path = config.output.vtu ? output.pvd_path() : "";

  const auto& factors = config.loading.factors;
  const int total = static_cast<int>(factors.size());
  io::ProgressLine progress(total, !options.quiet);
  la::Vector u(n, dim), rhs(n, dim), internal(n, dim);
  std::vector<double> u_prev(static_cast<std::size_t>(n), 0.0), fint_prev(static_cast<std::size_t>(n), 0.0);
  double work = 0.0;

  for (int i = 0; i < total; ++i) {
    const double lambda = factors[static_cast<std::size_t>(i)];
    auto kept = [&](int done) {
      return done == 0 ? fmt::format("No increment completed (output directory {})", summary.output_directory)
                       : fmt::format("Results of increments 1..{} are in {}", done, summary.output_directory);
    };
    auto solve = [&]() {
      rhs.set_all(0.0);
      rhs.axpy(lambda, rhs_unit);
      try {
        summary.last_solve = solver.solve(rhs, u);
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
    if (failure) {
      // Re-equilibration at fixed load: prescribed dofs do not move, applied
      // forces are constant, so the external work is λ F·Δu exactly.
      const std::size_t before = failure->broken().size();
      const double dissipated_before = failure->dissipated();
      for (;;) {
        const auto bonds = failure->select(uv);
        if (bonds.empty()) break;
        if (rec.break_iterations == config.fracture.max_iterations) {
          progress.finish();
          output.write_increment_vtu(model, i + 1, lambda, uv, failure->fields());
          throw Error(fmt::format(
              "increment {}/{} (load factor {}): bonds still fail after {} bond-breaking iterations ({} "
              "failed "
              "in this increment, {} over the criterion now): the crack is running unstably at this load, or "
              "the iterations diverge. Use smaller load increments or raise [fracture] max_iterations. The "
              "state after the last iteration is written as increment {}; {}",
              i + 1, total, lambda, rec.break_iterations, failure->broken().size() - before, bonds.size(),
              i + 1, kept(i)));
        }
        ++rec.break_iterations;
        double max_stretch = 0.0;
        for (const auto& b : bonds) max_stretch = std::max(max_stretch, b.stretch);
        FailureEnergy energy_failed;
        try {
          energy_failed = failure->apply(bonds, K, A, rhs_unit, bc);
        } catch (const Error& e) {  // a part cut free with unbalanced loads (floating_parts.hpp)
          progress.finish();
          output.write_increment_vtu(model, i + 1, lambda, uv, failure->fields());
          throw Error(fmt::format(
              "increment {}/{} (load factor {}), bond-breaking iteration {}: {}. The displacement "
              "before this iteration is written as increment {}; {}",
              i + 1, total, lambda, rec.break_iterations, e.what(), i + 1, kept(i)));
        }
        output.add_failed_bonds(model, i + 1, rec.break_iterations, bonds, failure->s_crit());
        solver.set_operator(A, model.dofmap.node_coordinates(), dim);
        const std::vector<double> u_before = uv;
        solve();
        output.add_failure_row(i + 1, rec.break_iterations, bonds.size(), energy_failed,
                               max_stretch / failure->s_crit(), summary.last_solve.iterations);
        uv = u.to_std();
        for (std::size_t k = 0; k < uv.size(); ++k) work += lambda * F[k] * (uv[k] - u_before[k]);
      }
      if (rec.break_iterations > 0) {
        K.mult(u, internal);
        fint = internal.to_std();
      }
      rec.bonds_broken = failure->broken().size();
      rec.bonds_broken_increment = rec.bonds_broken - before;
      rec.dissipated = failure->dissipated();
      rec.dissipated_increment = rec.dissipated - dissipated_before;
      rec.overshoot = failure->overshoot();
      const CrackArea crack = failure->crack_area();
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
    if ((i + 1) % every == 0 || i + 1 == total)
      output.write_increment_vtu(model, i + 1, lambda, uv, failure ? failure->fields() : FractureFields{});

    summary.increments_done = i + 1;
    summary.displacement = uv;
    summary.reactions = rec.reactions;
    summary.strain_energy = energy;
    summary.external_work = work;
    summary.history.push_back(rec);
    progress.update(i + 1,
                    failure ? fmt::format("{} its, {} bonds failed ({} iterations)", rec.iterations,
                                          rec.bonds_broken_increment, rec.break_iterations)
                            : fmt::format("{} its, residual {:.1e}", rec.iterations, rec.relative_residual));
  }
  progress.finish();
  return summary;
}

}  // namespace perimorph::driver
