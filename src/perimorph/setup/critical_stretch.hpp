#pragma once
// The critical bond stretch of a run (THEORY §5): [fracture] s_crit as given,
// or from [fracture] G_c by the bulk closed form G_c = κ s_crit² of the
// calibrated kernel (κ = Calibration::gc_factor). The one place s_crit is
// derived; `run` (bond failure) and `gc` both call it.

#include "perimorph/casefile/case_config.hpp"

#include <optional>

namespace perimorph::setup {

struct Discretization;

enum class StretchSource { option, case_s_crit, case_G_c, unit };

struct CriticalStretch {
  double value = 1.0;
  StretchSource source = StretchSource::unit;  ///< unit: none given, figures are per s_crit²
};

/// s_crit from `option` when given (gc --s-crit), else the case's [fracture]
/// s_crit, else sqrt(G_c / κ) from its G_c, else 1 (source unit). Throws
/// InputError for an option ≤ 0 or not finite, and for G_c when κ is not
/// available (NaN for an anisotropic kernel, whose G_c depends on the plane).
CriticalStretch resolve_critical_stretch(const casefile::FractureSpec& fracture, double gc_factor,
                                         std::optional<double> option = std::nullopt);

/// The critical stretch of a model with [fracture] and [nonlocal]
/// (resolve_critical_stretch of its case and calibration).
double critical_stretch(const Discretization& model);

}  // namespace perimorph::setup
