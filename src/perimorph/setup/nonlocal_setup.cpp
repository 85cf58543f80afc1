#include "perimorph/setup/nonlocal_setup.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace perimorph::setup {

alpha::Profile alpha_profile(casefile::AlphaProfile p) {
  return p == casefile::AlphaProfile::heaviside ? alpha::Profile::heaviside
         : p == casefile::AlphaProfile::linear  ? alpha::Profile::linear
                                                : alpha::Profile::cubic;
}

alpha::AlphaField make_alpha_field(const casefile::CaseConfig& config) {
  const auto& spec = config.alpha;
  if (spec.regions.empty()) return alpha::AlphaField::constant(spec.value);
  std::vector<alpha::Region> regions;
  for (const auto& r : spec.regions) {
    alpha::Region region;
    region.transition = r.transition;
    region.profile = alpha_profile(r.profile);
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

namespace {

/// "[0, 24]": the first n components of v.
std::string point(const Vec3& v, int n) {
  return fmt::format("[{}]", fmt::join(v.data(), v.data() + n, ", "));
}

/// The shape of an [[alpha.region]] entry in the case file's words.
std::string describe_shape(const casefile::AlphaRegionSpec& r, int dim) {
  switch (r.shape) {
    case casefile::AlphaShapeKind::interval:
      return fmt::format("interval {} to {}", r.lower.x(), r.upper.x());
    case casefile::AlphaShapeKind::slab:
      return fmt::format("slab through {}, half_width {}", point(r.point, dim), r.half_width);
    case casefile::AlphaShapeKind::ball:
      return fmt::format("ball, center {}, radius {}", point(r.point, dim), r.radius);
    case casefile::AlphaShapeKind::cylinder:
      return fmt::format("cylinder through {}, radius {}", point(r.point, dim), r.radius);
    case casefile::AlphaShapeKind::box:
      return fmt::format("box {} to {}", point(r.lower, dim), point(r.upper, dim));
  }
  return "";
}

}  // namespace

void check_alpha_regions(const casefile::CaseConfig& config, const alpha::AlphaField& alpha,
                         const bonds::NonlocalPoints& points, const mesh::Mesh& mesh,
                         std::span<const fem::QuadraturePoint> rule, const WholeMeshChecks& whole) {
  const auto& regions = alpha.region_list();
  const int dim = config.dim();
  for (std::size_t k = 0; k < regions.size() && k < config.alpha.regions.size(); ++k) {
    auto reaches = [&](const Vec3& x) { return alpha::region_value(regions[k], x, dim) > 0.0; };
    bool reached = false;
    std::vector<Vec3> x(static_cast<std::size_t>(points.per_cell));
    for (Index c = 0; c < mesh.num_cells() && !reached; ++c) {
      bonds::point_positions(mesh, points, c, x.data());
      reached = std::any_of(x.begin(), x.end(), reaches);
    }
    for (Index c = 0; c < mesh.num_cells() && !reached; ++c)
      for (const auto& q : rule) reached = reached || reaches(assembly::physical_point(mesh, c, q.xi));
    if (whole.any(reached)) continue;
    const auto& spec = config.alpha.regions[k];
    const auto mesh_extent = whole.bounds_of(mesh);
    throw InputError(fmt::format(
        "{}: this alpha region ({}, transition {}) gives alpha > 0 at no quadrature point of the mesh, "
        "which spans {} to {}: it would leave alpha = 0 where it was meant to act. Move it onto the mesh, "
        "widen it or its transition, or remove it",
        spec.where.describe(), describe_shape(spec, dim), spec.transition, point(mesh_extent.first, dim),
        point(mesh_extent.second, dim)));
  }
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
    case casefile::KernelKind::pmb:
      k.shape = peridynamics::KernelShape::pmb;
      break;
  }
  k.horizon = spec.horizon;
  k.length = spec.length > 0 ? spec.length : spec.horizon;
  return k;
}

}  // namespace perimorph::setup
