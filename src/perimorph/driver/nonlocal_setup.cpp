#include "perimorph/driver/nonlocal_setup.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace perimorph::driver {

alpha::AlphaField make_alpha_field(const casefile::CaseConfig& config) {
  const auto& spec = config.alpha;
  if (spec.regions.empty()) return alpha::AlphaField::constant(spec.value);
  std::vector<alpha::Region> regions;
  for (const auto& r : spec.regions) {
    alpha::Region region;
    region.transition = r.transition;
    region.profile = r.profile == casefile::AlphaProfile::heaviside ? alpha::Profile::heaviside
                     : r.profile == casefile::AlphaProfile::linear  ? alpha::Profile::linear
                                                                    : alpha::Profile::cubic;
    switch (r.shape) {
      case casefile::AlphaShapeKind::interval:
        region.shape = alpha::Interval{r.lower.x(), r.upper.x()};
        break;
      case casefile::AlphaShapeKind::slab:
        region.shape = alpha::Slab{r.point, r.direction, r.half_width};
        break;
      case casefile::AlphaShapeKind::ball:
        region.shape = alpha::Ball{r.point, r.radius};
        break;
      case casefile::AlphaShapeKind::cylinder:
        region.shape = alpha::Cylinder{r.point, r.direction, r.radius};
        break;
      case casefile::AlphaShapeKind::box:
        region.shape = alpha::Box{r.lower, r.upper};
        break;
    }
    regions.push_back(region);
  }
  return alpha::AlphaField::regions(std::move(regions), config.dim());
}

peridynamics::Micromodulus make_kernel(const casefile::NonlocalSpec& spec) {
  peridynamics::Micromodulus k;
  switch (spec.kernel) {
    case casefile::KernelKind::constant:
      k.shape = peridynamics::KernelShape::constant;
      break;
    case casefile::KernelKind::conical:
      k.shape = peridynamics::KernelShape::conical;
      break;
    case casefile::KernelKind::exponential:
      k.shape = peridynamics::KernelShape::exponential;
      break;
    case casefile::KernelKind::gaussian:
      k.shape = peridynamics::KernelShape::gaussian;
      break;
  }
  k.horizon = spec.horizon;
  k.length = spec.length > 0 ? spec.length : spec.horizon;
  return k;
}

}  // namespace perimorph::driver
