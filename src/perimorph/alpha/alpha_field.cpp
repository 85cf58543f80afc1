#include "perimorph/alpha/alpha_field.hpp"

#include "perimorph/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace perimorph::alpha {

double profile_value(Profile p, double t) {
  t = std::clamp(t, 0.0, 1.0);
  switch (p) {
    case Profile::heaviside:
      return t < 0.5 ? 0.0 : 1.0;
    case Profile::linear:
      return t;
    case Profile::cubic:
      return t * t * (3.0 - 2.0 * t);
  }
  return 0.0;
}

namespace {

Vec3 project(const Vec3& x, int dim) {
  Vec3 p = Vec3::Zero();
  p.head(dim) = x.head(dim);
  return p;
}

struct DistanceVisitor {
  Vec3 x;
  int dim;
  double operator()(const Interval& s) const { return std::max({s.lower - x.x(), x.x() - s.upper, 0.0}); }
  double operator()(const Slab& s) const {
    return std::max(std::abs(s.normal.dot(x - s.point)) - s.half_width, 0.0);
  }
  double operator()(const Ball& s) const {
    return std::max((x - project(s.center, dim)).norm() - s.radius, 0.0);
  }
  double operator()(const Cylinder& s) const {
    const Vec3 r = x - s.point;
    return std::max((r - s.axis * s.axis.dot(r)).norm() - s.radius, 0.0);
  }
  double operator()(const Box& s) const {
    double d2 = 0.0;
    for (int i = 0; i < dim; ++i) {
      const double d = std::max({s.lower[i] - x[i], x[i] - s.upper[i], 0.0});
      d2 += d * d;
    }
    return std::sqrt(d2);
  }
};

}  // namespace

double distance(const Shape& shape, const Vec3& x, int dim) {
  return std::visit(DistanceVisitor{project(x, dim), dim}, shape);
}

AlphaField AlphaField::constant(double value) {
  PERIMORPH_ASSERT(value >= 0.0 && value <= 1.0, "alpha must lie in [0, 1]");
  AlphaField f;
  f.constant_ = value;
  return f;
}

AlphaField AlphaField::regions(std::vector<Region> regions, int dim) {
  AlphaField f;
  f.dim_ = dim;
  for (auto& r : regions) {
    if (auto* s = std::get_if<Slab>(&r.shape)) s->normal.normalize();
    if (auto* c = std::get_if<Cylinder>(&r.shape)) c->axis.normalize();
  }
  f.regions_ = std::move(regions);
  return f;
}

AlphaField AlphaField::exactly(double constant, int dim, std::vector<Region> regions) {
  AlphaField f;
  f.constant_ = constant;
  f.dim_ = dim;
  f.regions_ = std::move(regions);
  return f;
}

AlphaField AlphaField::grown(std::vector<Region> added, int dim) const {
  PERIMORPH_ASSERT(!is_constant() || constant_ == 0.0, "a constant alpha > 0 cannot grow by regions");
  if (added.empty()) return *this;
  std::vector<Region> all = regions_;
  all.insert(all.end(), std::make_move_iterator(added.begin()), std::make_move_iterator(added.end()));
  return regions(std::move(all), is_constant() ? dim : dim_);
}

double region_value(const Region& r, const Vec3& x, int dim) {
  const double d = distance(r.shape, x, dim);
  if (d <= 0.0) return 1.0;
  if (d >= r.transition) return 0.0;
  return profile_value(r.profile, 1.0 - d / r.transition);
}

double AlphaField::operator()(const Vec3& x) const {
  if (regions_.empty()) return constant_;
  double a = 0.0;
  for (const Region& r : regions_) {
    a = std::max(a, region_value(r, x, dim_));
    if (a >= 1.0) break;
  }
  return a;
}

}  // namespace perimorph::alpha
