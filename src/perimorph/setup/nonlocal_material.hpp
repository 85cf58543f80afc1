#pragma once
// The material of a non-local case, made representable by central forces
// (THEORY §2, §2.1), and the micromodulus calibrated to it. A bond-based
// material obeys the Cauchy relations (C1212 = C1122, ...): shear moduli left
// out are set from them; given ones that break them are an input error naming
// the relation, unless the case accepts the nearest central-force tensor
// (cauchy = "nearest").

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace perimorph::setup {

struct NonlocalMaterial {
  casefile::MaterialSpec spec;  ///< as given
  peridynamics::AngularKind kind = peridynamics::AngularKind::isotropic;
  /// Isotropic (and 1D): Young's modulus and Poisson ratio of the calibration.
  double E = 0.0, nu = 0.0;
  /// Anisotropic kinds: the 3D central-force stiffness in material axes.
  Voigt6 C_material = Voigt6::Zero();
  /// The local stiffness C₀ in mesh axes, model dimension (Voigt).
  Eigen::MatrixXd C0;
  /// Values the resolution set or changed, one sentence each (for `info`).
  std::vector<std::string> notes;
};

/// Resolves the single material of a case with [nonlocal]. Throws InputError
/// (file, line, key, the relation and by how much) when it cannot be
/// represented.
NonlocalMaterial nonlocal_material(const casefile::CaseConfig& config);

/// Calibrates `kernel` (shape, δ, l set) to the material: sets the angular
/// part and returns the calibration (scale ĉ; for anisotropic kinds ĉ = 1,
/// the coefficients of Y carry the modulus, and λ, E, ν, κ are NaN).
peridynamics::Calibration calibrate_kernel(peridynamics::Micromodulus& kernel,
                                           const NonlocalMaterial& material, int dim, PlaneMode mode);

}  // namespace perimorph::setup
