#pragma once
// The commands of the perimorph program (commands.cpp): each reads a case
// file, hands it to the library (setup, run, diagnostics) and prints what it found. main (perimorph.cpp)
// parses the command line and reports errors; these throw perimorph errors.

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace perimorph::app {

/// Builds the case as `run` does before its first solve (model, constraints,
/// loads, reaction sets, fracture set-up) without assembling or solving;
/// `print` false: silent (the processes but the first under mpirun).
int check(const std::string& path, bool print = true);

/// Calibration and discretization figures of a case; with partition_parts > 0
/// also the partition report (diagnostics/partition_report.hpp).
int info(const std::string& path, int partition_parts = 0);

/// The residual of u = strain · x on every dof (THEORY §3.2), as CSV and VTU.
int ghost_forces(const std::string& path, const std::vector<double>& strain, const std::string& out_dir);

/// The critical energy release rate of a crack plane (diagnostics/effective_gc.hpp).
int gc(const std::string& path, std::vector<double> point, std::vector<double> normal,
       std::optional<double> s_option);

/// Runs a case; `petsc_args` go to PETSc's options database. Times on the
/// progress line count from `start` (the program's start). `restart`: a
/// checkpoint to continue ("" none); `checkpoint_every` ≥ 0 overrides the
/// case's [output] checkpoint_every.
int run(const std::string& path, const std::string& out_dir, bool quiet, std::vector<std::string> petsc_args,
        std::chrono::steady_clock::time_point start, const std::string& restart = "",
        int checkpoint_every = -1);

}  // namespace perimorph::app
