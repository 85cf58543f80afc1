// Secant (fixed point) against Newton through PETSc SNES for the local damage
// solve of an increment (issue 15, THEORY §6; docs/benchmarks/damage-solver.md).
//
// The model: a case with a damageable material and no [nonlocal] (the B8
// specimen's local damage model alone: examples/b8_damage_handover_3d/
// local_alone.toml), on a mesh and a load path given here. The case is run
// twice through perimorph's own run loop (run::run_static), once with each
// `[damage] solver`:
//
//   secant   the thesis' fixed point (evolution/local_damage.cpp, fig. 3.22):
//            solve with the secant stiffness (1 − d) C₀ (updated by
//            downdates), update d at every point, again until max Δd ≤ the
//            case's [damage] tolerance; linear solves = 1 + re-solves.
//   newton   before each damage update, evolution/damage_newton.cpp solves
//            the increment with the consistent tangent (SNES, at most 12
//            steps, each one LU solve); the fixed point's own check then ends
//            the increment (it finishes an increment where Newton failed);
//            linear solves = 1 + re-solves + Newton steps.
//
// Every linear system is solved by LU (-ksp_type preonly -pc_type lu and
// SNES's default), so a solve costs about the same in both and the count of
// solves is the cost to compare; the wall and CPU time of each run are
// printed beside it.
//
//   damage_solver_bench CASE nx ny nz INCREMENTS [d_c]   → JSON on stdout
//
// d_c, if given, overrides the material's (the hybrid's d_c = 0.2: the
// hardening branch the hybrid sees before the handover).

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace perimorph;

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  }
  double cpu_s() const { return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

struct IncrementResult {
  int solves = 0, updates = 0, newton_steps = 0;
  double reaction = 0.0, max_d = 0.0;
};

struct PathResult {
  std::vector<IncrementResult> increments;
  double wall_s = 0.0, cpu_s = 0.0;
};

/// Runs the case with `solver`; the reaction is the x component on the set "xmax".
PathResult run_path(casefile::CaseConfig config, casefile::DamageSolver solver) {
  config.damage.solver = solver;
  const auto dir =
      std::filesystem::temp_directory_path() /
      fmt::format("damage_solver_bench_{}", solver == casefile::DamageSolver::newton ? "newton" : "secant");
  Clock clock;
  const setup::Discretization model = setup::build_discretization(config);
  const run::RunSummary summary = run::run_static(model, {dir.string(), true, nullptr});
  PathResult out{{}, clock.wall_s(), clock.cpu_s()};
  const auto xmax = std::find(summary.reaction_names.begin(), summary.reaction_names.end(), "xmax");
  const auto set = static_cast<std::size_t>(xmax - summary.reaction_names.begin());
  for (const run::IncrementRecord& r : summary.history)
    out.increments.push_back({1 + r.break_iterations + r.damage_newton_steps, r.damage_iterations,
                              r.damage_newton_steps, set < r.reactions.size() ? r.reactions[set].x() : 0.0,
                              r.max_damage});
  std::filesystem::remove_all(dir);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    fmt::print(stderr, "usage: {} CASE nx ny nz INCREMENTS [d_c]\n", argv[0]);
    return 2;
  }
  la::PetscSession petsc;
  auto config = casefile::parse_case_file(argv[1]);
  config.mesh.box.cells = {static_cast<Index>(std::stoi(argv[2])), static_cast<Index>(std::stoi(argv[3])),
                           static_cast<Index>(std::stoi(argv[4]))};
  const int n = std::stoi(argv[5]);
  config.loading.factors.clear();
  for (int i = 1; i <= n; ++i) config.loading.factors.push_back(static_cast<double>(i) / n);
  double d_c = 0.0;
  for (auto& m : config.materials)
    if (m.damage.enabled) {
      if (argc > 6) m.damage.d_c = std::stod(argv[6]);
      d_c = m.damage.d_c;
    }
  config.solver.petsc_options = "-ksp_type preonly -pc_type lu";
  config.output.vtu = false;
  const PathResult secant = run_path(config, casefile::DamageSolver::secant);
  const PathResult newton = run_path(config, casefile::DamageSolver::newton);

  fmt::print(
      "{{\"case\": \"{}\", \"cells\": [{}, {}, {}], \"increments\": {}, \"d_c\": {}, \"tolerance\": {},\n",
      argv[1], argv[2], argv[3], argv[4], n, d_c, config.damage.tolerance);
  fmt::print(
      " \"secant\": {{\"wall_s\": {:.3f}, \"cpu_s\": {:.3f}}}, \"newton\": {{\"wall_s\": {:.3f}, \"cpu_s\": "
      "{:.3f}}},\n",
      secant.wall_s, secant.cpu_s, newton.wall_s, newton.cpu_s);
  fmt::print(" \"increments_table\": [\n");
  const std::size_t rows = std::min(secant.increments.size(), newton.increments.size());
  for (std::size_t i = 0; i < rows; ++i) {
    const auto& s = secant.increments[i];
    const auto& w = newton.increments[i];
    fmt::print(
        "  {{\"increment\": {}, \"secant_solves\": {}, \"secant_updates\": {}, \"secant_reaction\": {:.10g}, "
        "\"secant_max_d\": {:.6g}, \"newton_solves\": {}, \"newton_steps\": {}, \"newton_updates\": {}, "
        "\"newton_reaction\": {:.10g}, \"newton_max_d\": {:.6g}}}{}\n",
        i + 1, s.solves, s.updates, s.reaction, s.max_d, w.solves, w.newton_steps, w.updates, w.reaction,
        w.max_d, i + 1 < rows ? "," : "");
  }
  fmt::print(" ]}}\n");
  return 0;
}
