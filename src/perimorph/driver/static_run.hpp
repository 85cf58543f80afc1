#pragma once
// The quasi-static driver of the local model (issue 2): for each increment of
// the load ramp, solve K u = F with the constraints eliminated, then report
// reactions, energies and fields. Later stages (bond breaking, damage,
// adaptivity) plug into the same loop.

#include "perimorph/driver/model.hpp"
#include "perimorph/driver/run_output.hpp"
#include "perimorph/la/linear_solver.hpp"

#include <string>
#include <vector>

namespace perimorph::driver {

struct RunOptions {
  std::string output_directory;  ///< overrides the case's [output] directory if not empty
  bool quiet = false;            ///< no progress line
};

struct RunSummary {
  int increments_done = 0;
  std::vector<double> displacement;  ///< last solution (dof vector)
  std::vector<std::string> reaction_names;
  std::vector<Vec3> reactions;  ///< last increment, per reaction set
  double strain_energy = 0.0;
  double external_work = 0.0;
  la::SolveReport last_solve;
  std::vector<IncrementRecord> history;  ///< one record per completed increment (what the CSV holds)
  std::string output_directory, csv_path, pvd_path;
};

/// Output directory of a case: the override if given, else the case's
/// [output] directory resolved against the case file's folder.
std::string resolve_output_directory(const casefile::CaseConfig& config, const RunOptions& options);

/// Runs every increment. PETSc options of the case are inserted first (the
/// command line keeps precedence). On a solver failure throws SolverError
/// saying which increment failed; what was computed before stays on disk.
RunSummary run_static(const Model& model, const RunOptions& options);

}  // namespace perimorph::driver
