#include "perimorph/core/hole.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace perimorph {

namespace {
/// "[0, 24]": the first n components of v.
std::string point(const Vec3& v, int n) {
  return fmt::format("[{}]", fmt::join(v.data(), v.data() + n, ", "));
}
}  // namespace

bool Hole::contains(const Vec3& x) const {
  switch (shape) {
    case HoleShape::disk:
    case HoleShape::cylinder:
      return (x - center).head<2>().squaredNorm() < radius * radius;
    case HoleShape::ball:
      return (x - center).squaredNorm() < radius * radius;
    case HoleShape::box:
      for (int d = 0; d < dim; ++d)
        if (!(x[d] > lower[d] && x[d] < upper[d])) return false;
      return true;
  }
  return false;
}

std::string Hole::describe() const {
  switch (shape) {
    case HoleShape::disk:
      return fmt::format("disk of radius {} centred at {}", radius, point(center, dim));
    case HoleShape::ball:
      return fmt::format("ball of radius {} centred at {}", radius, point(center, dim));
    case HoleShape::cylinder:
      return fmt::format("cylinder of radius {} around the z-parallel axis through {}", radius,
                         point(center, dim));
    case HoleShape::box:
      return fmt::format("box {} to {}", point(lower, dim), point(upper, dim));
  }
  return {};
}

}  // namespace perimorph
