#pragma once
// The typed form of a case file's loads, solver and output (part of
// CaseConfig, casefile/case_config.hpp): [[dirichlet]], [[traction]],
// [loading], [solver], [output]. Documented in docs/case-file.md.

#include "perimorph/casefile/source_location.hpp"
#include "perimorph/core/types.hpp"

#include <array>
#include <string>
#include <vector>

namespace perimorph::casefile {

/// [[dirichlet]]: on a node set (or the nodes of a face/cell set), prescribes
/// u_c = value_c + Σ_j gradient_cj x_j for each constrained component c,
/// scaled by the load factor.
struct DirichletSpec {
  std::string set;
  std::array<bool, 3> constrained{false, false, false};
  Vec3 value = Vec3::Zero();
  Mat3 gradient = Mat3::Zero();
  SourceLocation where;
};

/// [[traction]]: a constant traction vector (force per area) on a face set.
struct TractionSpec {
  std::string set;
  Vec3 value = Vec3::Zero();
  SourceLocation where;
};

/// [loading]: load factors of the increments. Either `increments` = N with a
/// linear ramp (factors i/N, i = 1..N), or an explicit list `factors`.
struct LoadingSpec {
  std::vector<double> factors{1.0};
  Vec3 body_force = Vec3::Zero();  ///< force per volume, scaled by the load factor
};

/// How the stiffness reaches the solver: `assembled` (a sparse matrix), or
/// `matrix_free` (the non-local operator of a structured grid applied from
/// one block per grid offset, preconditioned by an assembled short-horizon
/// operator; setup::check_matrix_free states the cases it covers).
enum class SolverOperator { assembled, matrix_free };

/// [solver]
struct SolverSpec {
  std::string petsc_options;  ///< e.g. "-ksp_type preonly -pc_type cholesky"
  double rtol = 1e-10;
  int max_iterations = 10000;
  SolverOperator op = SolverOperator::assembled;  ///< key `operator`
  /// Matrix-free: the horizon of the preconditioning operator, in units of the
  /// largest cell edge (key `preconditioner_horizon`).
  double preconditioner_horizon = 1.5;
  SourceLocation operator_where;  ///< the `operator` key (the [solver] table when absent)
};

/// [output]
struct OutputSpec {
  std::string directory = "output";  ///< relative to the case file's folder unless absolute
  std::string basename;              ///< default: case file stem
  bool vtu = true;
  int every = 1;              ///< write VTU every n increments (and always the last)
  bool failed_bonds = false;  ///< fracture runs: BASENAME_failed_bonds.csv, one row per failed bond
  /// BASENAME.checkpoint every n increments (0: only when the run is stopped
  /// by SIGINT/SIGTERM between increments); run/checkpoint.hpp.
  int checkpoint_every = 0;
};

}  // namespace perimorph::casefile
