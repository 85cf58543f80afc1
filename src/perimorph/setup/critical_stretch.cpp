#include "perimorph/setup/critical_stretch.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>

#include <cmath>

namespace perimorph::setup {

CriticalStretch resolve_critical_stretch(const casefile::FractureSpec& fracture, double gc_factor,
                                         std::optional<double> option) {
  if (option) {
    if (!(*option > 0.0) || !std::isfinite(*option))
      throw InputError(
          fmt::format("--s-crit must be a positive number (a critical bond stretch such as "
                      "1e-3); got {}",
                      *option));
    return {*option, StretchSource::option};
  }
  if (fracture.enabled && fracture.s_crit > 0.0) return {fracture.s_crit, StretchSource::case_s_crit};
  if (fracture.enabled && fracture.G_c > 0.0) {
    if (!std::isfinite(gc_factor) || gc_factor <= 0.0)
      throw InputError(fmt::format(
          "{}: G_c = {} cannot be turned into a critical stretch: the bulk closed form G_c = kappa s_crit^2 "
          "(THEORY §5) is only available for an isotropic kernel; give s_crit instead (in [fracture], or "
          "--s-crit for gc)",
          fracture.where.describe(), fracture.G_c));
    return {std::sqrt(fracture.G_c / gc_factor), StretchSource::case_G_c};
  }
  return {1.0, StretchSource::unit};
}

double critical_stretch(const Discretization& model) {
  const auto& spec = model.config.fracture;
  PERIMORPH_ASSERT(spec.enabled && model.nonlocal, "critical_stretch needs [fracture] and [nonlocal]");
  return resolve_critical_stretch(spec, model.nonlocal->calibration.gc_factor).value;
}

}  // namespace perimorph::setup
