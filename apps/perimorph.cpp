// perimorph: the command-line program. A thin layer: parse the command line,
// read the case file, hand over to the library (setup, run, diagnostics),
// report errors once.
//
//   perimorph check CASE                 validate a case file without running
//   perimorph info CASE                  calibration and discretization figures
//   perimorph run CASE [-o DIR] [--quiet] [--restart PATH] [--checkpoint-every N] [PETSc options...]
//   perimorph ghost-forces CASE --strain ... [-o DIR]
//   perimorph gc CASE --point X [Y [Z]] --normal NX [NY [NZ]] [--s-crit S]
//
// PETSc options are told from the program's own before CLI11 sees them
// (split_arguments): CLI11 would read "-options_left" as "-o ptions_left".

#include "commands.hpp"

#include "perimorph/casefile/suggest.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/core/interrupt.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

const char* perimorph_build_commit();  // generated at build time (cmake/write_version.cmake)

namespace {

/// A first argument that is neither an option nor a command: name it, suggest
/// the closest command and list them (CLI11 alone reports it as a missing
/// command). Returns the message, or "" when the first argument is fine.
std::string unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return {};
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const std::string word = argv[1];
  if (std::find(names.begin(), names.end(), word) != names.end()) return {};
  const std::string near = perimorph::casefile::closest_match(word, names);
  return fmt::format("unknown command '{}'{}; the commands are {} (perimorph --help)", word,
                     near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), fmt::join(names, ", "));
}

/// A word PETSc reads as an option name: '-' and a letter ("-ksp_type",
/// "-o"); "--output" and "-1e-3" are not.
bool option_like(std::string_view w) {
  return w.size() >= 2 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1])) != 0;
}

struct Arguments {
  std::vector<std::string> program;  ///< for CLI11: the program, the command, its arguments
  std::vector<std::string> petsc;    ///< PETSc options, each followed by its value if it has one
};

/// Splits the arguments after the command: a single-dash word of three or
/// more characters ("-ksp_type", "-options_left") is a PETSc option, and the
/// word after it its value unless that word is option-like (PETSc's own
/// rule); everything else ("-o DIR", "--quiet", the case file, and all after
/// "--") is the program's.
Arguments split_arguments(int argc, char** argv) {
  Arguments out;
  for (int i = 0; i < std::min(argc, 2); ++i) out.program.emplace_back(argv[i]);
  for (int i = 2; i < argc; ++i) {
    const std::string_view w = argv[i];
    if (w == "--") {
      out.program.insert(out.program.end(), argv + i, argv + argc);
      break;
    }
    if (w.size() > 2 && option_like(w)) {
      out.petsc.emplace_back(w);
      if (i + 1 < argc && !option_like(argv[i + 1])) out.petsc.emplace_back(argv[++i]);
      continue;
    }
    out.program.emplace_back(w);
  }
  return out;
}

/// The rank mpirun gave this process (from its environment; 0 when started
/// alone): the messages of main are printed after PETSc, and MPI with it, has
/// ended.
int launcher_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return 0;
}

/// Prints an error of a command. Under mpirun, every process of a distributed
/// run computes the same figures and meets the same input, solver and stop
/// errors: process 0 alone prints those (`everywhere` false); others (an
/// output error of process 0, which alone writes) are printed by the process
/// that met them, named.
void report(const char* prefix, const char* what, bool everywhere) {
  const int rank = launcher_rank();
  if (rank == 0)
    fmt::print(stderr, "{}{}\n", prefix, what);
  else if (everywhere)
    fmt::print(stderr, "process {}: {}{}\n", rank, prefix, what);
}

}  // namespace

int main(int argc, char** argv) {
  const auto start = std::chrono::steady_clock::now();
  CLI::App app{
      "perimorph — hybrid local/non-local (peridynamics) fracture simulator.\n"
      "Case-file format: docs/case-file.md. PETSc options (e.g. -ksp_type preonly -pc_type cholesky) may\n"
      "follow the case file of `run`; they override the case's [solver] petsc_options."};
  app.require_subcommand(1);
  app.set_version_flag("--version",
                       fmt::format("perimorph {} (commit {})", PERIMORPH_VERSION, perimorph_build_commit()));

  std::string case_path;
  auto* check_cmd =
      app.add_subcommand("check", "Validate a case file (and build its mesh) without running it");
  check_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();

  auto* info_cmd = app.add_subcommand("info",
                                      "Print the calibrated micromodulus (scale, equivalent lambda = mu, E, "
                                      "nu, G_c factor) and the discretization figures of a case");
  info_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  int partition_parts = 0;
  info_cmd
      ->add_option("--partition", partition_parts,
                   "Also print how P ranks would split the cells (coordinate bisection, PT-Scotch) and the "
                   "halo each would hold")
      ->check(CLI::Range(1, 1 << 20));

  std::string out_dir;
  bool quiet = false;
  auto* run_cmd = app.add_subcommand("run", "Run a case: every load increment, VTU/PVD and CSV output");
  run_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  run_cmd->add_option("-o,--output", out_dir, "Output directory (default: the case's [output] directory)");
  run_cmd->add_flag("-q,--quiet", quiet, "No progress line and no summary");
  std::string restart;
  int checkpoint_every = -1;
  run_cmd->add_option(
      "--restart", restart,
      "Continue a run from its checkpoint: a BASENAME.checkpoint file, or the output directory "
      "holding it (the same case file; docs/output.md, Restart)");
  run_cmd
      ->add_option(
          "--checkpoint-every", checkpoint_every,
          "Write BASENAME.checkpoint every N increments (overrides [output] checkpoint_every; 0: only "
          "when stopped by SIGINT/SIGTERM)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  run_cmd->footer(
      "PETSc options follow the case file: every word of the form -name (a dash and two or more characters, "
      "e.g. -ksp_type cg, -options_file F, -options_left) is passed to PETSc's options database with the "
      "value after it, and wins over the case's [solver] petsc_options. Options PETSc did not use are "
      "reported "
      "after the first solve. Any other extra argument is an error.");

  std::vector<double> strain;
  auto* ghost_cmd = app.add_subcommand(
      "ghost-forces",
      "Impose u = strain * x on every degree of freedom and write the residual (ghost forces) and its "
      "density per nodal volume, as VTU and CSV (THEORY §3.2)");
  ghost_cmd->add_option("CASE", case_path, "Case file (TOML)")->required();
  ghost_cmd
      ->add_option("--strain", strain,
                   "Imposed strain: exx (1D); exx,eyy,exy (2D); exx,eyy,ezz,eyz,exz,exy "
                   "(3D), tensorial shear")
      ->required()
      ->delimiter(',');
  ghost_cmd->add_option("-o,--output", out_dir, "Output directory (default: the case's [output] directory)");

  std::vector<double> gc_point, gc_normal;
  std::optional<double> gc_s_crit;
  auto* gc_cmd = app.add_subcommand(
      "gc",
      "Critical energy release rate of the crack plane through --point with normal --normal: the bulk closed "
      "form kappa s_crit^2, the actual geometry (every bond crossing the plane, incomplete horizons near "
      "free faces included, pre-cracked bonds left out) and the bulk window (crossings farther than delta "
      "from every face) (THEORY §5)");
  gc_cmd->add_option("CASE", case_path, "Case file (TOML) with a [nonlocal] section")->required();
  gc_cmd
      ->add_option("--point", gc_point,
                   "A point of the plane, one number per axis of the case (in 2D a third, z, may be 0)")
      ->required()
      ->expected(1, 3)
      ->type_name("X [Y [Z]]");
  gc_cmd
      ->add_option("--normal", gc_normal,
                   "The plane's normal, any length; in 2D without z component, in 1D 1 0 0")
      ->required()
      ->expected(1, 3)
      ->type_name("NX [NY [NZ]]");
  gc_cmd->add_option("--s-crit", gc_s_crit,
                     "Critical bond stretch (default: the case's [fracture] s_crit, or s_crit from its G_c; "
                     "else the figures are per s_crit^2)");
  gc_cmd->footer(
      "Any crack plane of a box: its area inside the box is computed for any normal (a polygon in 3D, a "
      "segment times the thickness in 2D).");

  // Under mpirun every process meets a command-line error: process 0 prints it.
  const bool first_process = launcher_rank() == 0;
  if (const std::string message = unknown_command(app, argc, argv); !message.empty()) {
    if (first_process) fmt::print(stderr, "error: {}\n", message);
    return 2;
  }
  const Arguments args = split_arguments(argc, argv);
  const bool run_command = argc >= 2 && std::string_view(argv[1]) == "run";
  if (!args.petsc.empty() && !run_command) {
    if (first_process)
      fmt::print(stderr,
                 "error: {} {} not an option of `{}`; PETSc options are taken only by `run`, after the case "
                 "file (perimorph {} --help)\n",
                 fmt::join(args.petsc, " "), args.petsc.size() == 1 ? "is" : "are", argv[1], argv[1]);
    return 2;
  }
  try {
    std::vector<const char*> program;
    for (const auto& a : args.program) program.push_back(a.c_str());
    app.parse(static_cast<int>(program.size()), program.data());
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or --help); a command-line error exits 2 like
    // any input error (docs/output.md), not with CLI11's own codes (105, 106, ...).
    std::ostringstream discarded;
    const int code = first_process ? app.exit(e) : app.exit(e, discarded, discarded);
    return code == 0 ? 0 : 2;
  }

  try {
    using namespace perimorph::app;
    if (*check_cmd) return check(case_path, first_process);
    if (*info_cmd) return info(case_path, partition_parts);
    if (*ghost_cmd) return ghost_forces(case_path, strain, out_dir);
    if (*gc_cmd) return gc(case_path, gc_point, gc_normal, gc_s_crit);
    return run(case_path, out_dir, quiet, args.petsc, start, restart, checkpoint_every);
  } catch (const perimorph::StoppedByProcessZero& e) {  // process 0 prints why
    return e.output ? 5 : 4;
  } catch (const perimorph::Interrupted& e) {
    report("stopped: ", e.what(), false);
    return 128 + e.signal;
  } catch (const perimorph::InputError& e) {
    report("error: ", e.what(), false);
    return 2;
  } catch (const perimorph::OutputError& e) {
    report("error: ", e.what(), true);
    return 5;
  } catch (const perimorph::SolverError& e) {
    report("solver error: ", e.what(), false);
    return 3;
  } catch (const perimorph::RunStopped& e) {
    report("error: ", e.what(), false);
    return 4;
  } catch (const std::exception& e) {
    report("error: ", e.what(), true);
    return 4;
  }
}
