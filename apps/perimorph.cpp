// perimorph: the command-line program. A thin layer: parse the command line,
// read the case file, hand over to the driver, report errors once.
//
//   perimorph check CASE                 validate a case file without running
//   perimorph run CASE [-o DIR] [--quiet] [PETSc options...]

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/driver/model.hpp"
#include "perimorph/driver/static_run.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

int check(const std::string& path) {
  const auto config = perimorph::casefile::parse_case_file(path);
  const auto model = perimorph::driver::build_model(config);
  fmt::print("{}: OK — {}D, {} cells, {} nodes, {} dofs, {} material(s), {} increment(s)\n", path, model.dim(),
             model.mesh.num_cells(), model.mesh.num_nodes(), model.dofmap.num_dofs(), config.materials.size(),
             config.loading.factors.size());
  return 0;
}

int run(const std::string& path, const std::string& out_dir, bool quiet, std::vector<std::string> petsc_args) {
  const auto config = perimorph::casefile::parse_case_file(path);
  // PETSc sees only the options meant for it (the program name first).
  std::vector<std::string> args{"perimorph"};
  args.insert(args.end(), petsc_args.begin(), petsc_args.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(args.size());
  char** argv_ptr = argv.data();
  perimorph::la::PetscSession petsc(argc, argv_ptr);
  const auto model = perimorph::driver::build_model(config);
  const auto summary = perimorph::driver::run_static(model, {out_dir, quiet});
  if (!quiet) {
    fmt::print("{}: {} increment(s), {} dofs; last solve {} + {}: {} iterations, relative residual {:.2e}\n", path,
               summary.increments_done, model.dofmap.num_dofs(), summary.last_solve.ksp_type,
               summary.last_solve.pc_type, summary.last_solve.iterations, summary.last_solve.relative_residual);
    fmt::print("strain energy {:.6e}, external work {:.6e}\n", summary.strain_energy, summary.external_work);
    for (std::size_t k = 0; k < summary.reactions.size(); ++k)
      fmt::print("reaction on '{}': ({:.6e}, {:.6e}, {:.6e})\n", summary.reaction_names[k], summary.reactions[k].x(),
                 summary.reactions[k].y(), summary.reactions[k].z());
    fmt::print("wrote {}{}\n", summary.csv_path, summary.pvd_path.empty() ? "" : " and " + summary.pvd_path);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"perimorph — hybrid local/non-local (peridynamics) fracture simulator.\n"
               "Case-file format: docs/case-file.md. PETSc options (e.g. -ksp_type preonly -pc_type cholesky) may\n"
               "follow the case file of `run`; they override the case's [solver] petsc_options."};
  app.require_subcommand(1);

  std::string case_path;
  auto* check_cmd = app.add_subcommand("check", "Validate a case file (and build its mesh) without running it");
  check_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();

  std::string out_dir;
  bool quiet = false;
  auto* run_cmd = app.add_subcommand("run", "Run a case: every load increment, VTU/PVD and CSV output");
  run_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  run_cmd->add_option("-o,--output", out_dir, "Output directory (default: the case's [output] directory)");
  run_cmd->add_flag("-q,--quiet", quiet, "No progress line and no summary");
  run_cmd->allow_extras();
  run_cmd->footer("Any further argument starting with '-' is passed to PETSc's options database.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*check_cmd) return check(case_path);
    return run(case_path, out_dir, quiet, run_cmd->remaining());
  } catch (const perimorph::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const perimorph::SolverError& e) {
    fmt::print(stderr, "solver error: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 4;
  }
}
