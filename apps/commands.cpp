// The commands of the perimorph program (commands.hpp).

#include "commands.hpp"

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/core/interrupt.hpp"
#include "perimorph/diagnostics/case_report.hpp"
#include "perimorph/diagnostics/ghost_forces.hpp"
#include "perimorph/diagnostics/partition_report.hpp"
#include "perimorph/io/progress.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

namespace perimorph::app {

namespace {

/// The model with every bond in its cell graph, for the commands that count
/// or assemble bonds (info, ghost-forces, gc): a matrix-free case's run
/// alone builds it without (setup::Discretization::nonlocal). The case's
/// operator is checked all the same.
perimorph::setup::Discretization model_with_bonds(const perimorph::casefile::CaseConfig& config) {
  perimorph::setup::check_matrix_free(config);
  perimorph::casefile::CaseConfig assembled = config;
  assembled.solver.op = perimorph::casefile::SolverOperator::assembled;
  return perimorph::setup::build_discretization(assembled);
}

}  // namespace

int check(const std::string& path, bool print) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const auto model = perimorph::setup::build_discretization(config);
  // What `run` builds before its first solve, so that check finds every case
  // error run would find (set names, loads, the critical stretch, ...).
  const auto setup = perimorph::run::prepare_run(model);
  if (!print) return 0;
  fmt::print(
      "{}: OK — {}D, {} cells, {} nodes, {} dofs, {} material(s), {} increment(s), {} constrained dofs\n",
      path, model.dim(), model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_dofs(),
      config.materials.size(), config.loading.factors.size(), setup.bc.dofs.size());
  return 0;
}

namespace {

/// A PETSc session with no options of its own (commands that assemble but do
/// not solve). Under mpirun every process computes the command's figures
/// (ghost-forces spreads its K over them) and process 0 alone prints and
/// writes them (print_once).
std::unique_ptr<perimorph::la::PetscSession> quiet_petsc() {
  return std::make_unique<perimorph::la::PetscSession>();
}

/// Prints `text` on standard output from process 0 only.
void print_once(const std::string& text) {
  if (perimorph::la::world_rank() == 0) fmt::print("{}", text);
}

}  // namespace

int info(const std::string& path, int partition_parts) {
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = model_with_bonds(config);
  print_once(perimorph::diagnostics::info_report(model, path));
  if (partition_parts > 0) print_once(perimorph::diagnostics::partition_report(model, partition_parts));
  return 0;
}

int ghost_forces(const std::string& path, const std::vector<double>& strain, const std::string& out_dir) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const int dim = config.dim();
  const std::size_t expected = dim == 1 ? 1 : dim == 2 ? 3 : 6;
  if (strain.size() != expected)
    throw perimorph::InputError(fmt::format("--strain needs {} values in {}D ({}); got {}", expected, dim,
                                            dim == 1   ? "exx"
                                            : dim == 2 ? "exx,eyy,exy"
                                                       : "exx,eyy,ezz,eyz,exz,exy",
                                            strain.size()));
  perimorph::Mat3 eps = perimorph::Mat3::Zero();
  eps(0, 0) = strain[0];
  if (dim == 2) {
    eps(1, 1) = strain[1];
    eps(0, 1) = eps(1, 0) = strain[2];
  } else if (dim == 3) {
    eps(1, 1) = strain[1];
    eps(2, 2) = strain[2];
    eps(1, 2) = eps(2, 1) = strain[3];
    eps(0, 2) = eps(2, 0) = strain[4];
    eps(0, 1) = eps(1, 0) = strain[5];
  }
  auto petsc = quiet_petsc();
  const auto model = model_with_bonds(config);
  const auto g = perimorph::diagnostics::compute_ghost_forces(model, eps);
  if (perimorph::la::world_rank() != 0) return 0;  // process 0 writes
  const std::string dir = perimorph::run::resolve_output_directory(config, {out_dir, true});
  const std::string base =
      config.output.basename.empty() ? std::filesystem::path(path).stem().string() : config.output.basename;
  const auto csv = perimorph::diagnostics::write_ghost_forces(model, g, dir, base);
  fmt::print("max ghost-force density {:.6e}; wrote {}\n", g.max_density, csv);
  return 0;
}

/// The critical energy release rate of a crack plane: closed form, actual
/// geometry and bulk window (diagnostics/effective_gc.hpp).
int gc(const std::string& path, std::vector<double> point, std::vector<double> normal,
       std::optional<double> s_option) {
  const auto config = perimorph::casefile::parse_case_file(path);
  auto petsc = quiet_petsc();
  const auto model = model_with_bonds(config);
  // One number per axis of the case at least (a shorter vector would put the
  // plane somewhere the user did not say); a z of 0 may follow in 2D.
  for (const auto& [name, v] : {std::pair{"--point", &point}, std::pair{"--normal", &normal}})
    if (static_cast<int>(v->size()) < model.dim())
      throw perimorph::InputError(fmt::format("{} has {} number{} but {} is {}D: give one per axis ({})",
                                              name, v->size(), v->size() == 1 ? "" : "s", path, model.dim(),
                                              model.dim() == 2 ? "x y" : "x y z"));
  point.resize(3, 0.0);
  normal.resize(3, 0.0);
  const perimorph::Vec3 p(point[0], point[1], point[2]), n(normal[0], normal[1], normal[2]);
  print_once(perimorph::diagnostics::gc_report(model, path, p, n, s_option));
  return 0;
}

int run(const std::string& path, const std::string& out_dir, bool quiet, std::vector<std::string> petsc_args,
        std::chrono::steady_clock::time_point start, const std::string& restart, int checkpoint_every) {
  const auto config = perimorph::casefile::parse_case_file(path);
  perimorph::io::ProgressLine progress(static_cast<int>(config.loading.factors.size()), !quiet, start);
  progress.phase("PETSc");
  // PETSc sees only the options meant for it (the program name first).
  std::vector<std::string> args{"perimorph"};
  args.insert(args.end(), petsc_args.begin(), petsc_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(args.size());
  char** argv_ptr = argv.data();
  perimorph::la::PetscSession petsc(argc, argv_ptr);
  if (perimorph::la::world_rank() != 0) {  // process 0 reports; the others compute the same figures
    progress.mute();
    quiet = true;
  }
  // After PETSc's initialization (which installs its own handlers): SIGINT and
  // SIGTERM stop the run between solves, its files in step.
  perimorph::install_stop_handlers();
  const perimorph::run::RunOptions options{out_dir, quiet, &progress, restart, checkpoint_every};
  const auto summary = perimorph::run::run_static(
      perimorph::run::process_model(config, [&](const std::string& phase) { progress.phase(phase); }),
      options);
  progress.finish();
  if (!quiet) {
    if (summary.restarted_after > 0)
      fmt::print("continued after increment {} ({})\n", summary.restarted_after, restart);
    fmt::print("{}: {} increment(s), {} dofs; last solve {} + {}: {} iterations, relative residual {:.2e}\n",
               path, summary.increments_done, summary.dofs, summary.last_solve.ksp_type,
               summary.last_solve.pc_type, summary.last_solve.iterations,
               summary.last_solve.relative_residual);
    if (summary.preconditioner_rebuilds > 0)
      fmt::print("{} solves rebuilt the reused preconditioner (it failed, or the iterations had grown)\n",
                 summary.preconditioner_rebuilds);
    if (summary.direct_fallback_solves > 0)
      fmt::print(
          "{} solves were made by the direct fallback after Krylov failed on a matrix that bond failures "
          "left singular (MUMPS, up to {} null pivots held)\n",
          summary.direct_fallback_solves, summary.most_null_pivots);
    fmt::print("strain energy {:.6e}, external work {:.6e}\n", summary.strain_energy, summary.external_work);
    for (std::size_t k = 0; k < summary.reactions.size(); ++k)
      fmt::print("reaction on '{}': ({:.6e}, {:.6e}, {:.6e})\n", summary.reaction_names[k],
                 summary.reactions[k].x(), summary.reactions[k].y(), summary.reactions[k].z());
    std::vector<std::string> phases;
    for (const auto& ph : progress.phases())
      phases.push_back(fmt::format("{} {:.2f} s", ph.name, ph.seconds));
    fmt::print(
        "phases{}: {}\n",
        perimorph::la::world_size() > 1 ? fmt::format(" (process 0 of {})", perimorph::la::world_size()) : "",
        fmt::join(phases, ", "));
    fmt::print("wrote {}{}\n", summary.csv_path, summary.pvd_path.empty() ? "" : " and " + summary.pvd_path);
    if (!summary.checkpoint_path.empty() && summary.checkpoint_increment > summary.restarted_after)
      fmt::print("checkpoint of increment {}: {}\n", summary.checkpoint_increment, summary.checkpoint_path);
  }
  return 0;
}

}  // namespace perimorph::app
