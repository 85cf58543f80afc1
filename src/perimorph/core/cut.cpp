#include "perimorph/core/cut.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <utility>

namespace perimorph {

Vec3 Cut::normal() const {
  if (dim == 1) return Vec3::UnitX();
  if (dim == 2) return Vec3(-edge1.y(), edge1.x(), 0.0).normalized();
  return edge1.cross(edge2).normalized();
}

namespace {
/// Coordinates (s, t) of p's projection on the cut in the basis (edge1, edge2):
/// in 3D, with n = edge1 × edge2, s = ((p − o) × edge2)·n / |n|² and
/// t = (edge1 × (p − o))·n / |n|² (the out-of-plane part of p − o drops out).
std::pair<double, double> in_plane_coordinates(const Cut& cut, const Vec3& p) {
  const Vec3 r = p - cut.origin;
  if (cut.dim == 2) return {r.dot(cut.edge1) / cut.edge1.squaredNorm(), 0.0};
  const Vec3 n = cut.edge1.cross(cut.edge2);
  const double nn = n.squaredNorm();
  return {r.cross(cut.edge2).dot(n) / nn, cut.edge1.cross(r).dot(n) / nn};
}
}  // namespace

bool Cut::contains(const Vec3& p, double tol) const {
  if (dim == 1) return std::abs(p.x() - origin.x()) <= tol;
  if (std::abs((p - origin).dot(normal())) > tol) return false;
  auto [s, t] = in_plane_coordinates(*this, p);
  const double ts = tol / edge1.norm();
  if (s < -ts || s > 1 + ts) return false;
  if (dim == 3) {
    const double tt = tol / edge2.norm();
    if (t < -tt || t > 1 + tt) return false;
    if (triangle && s + t > 1 + ts + tt) return false;
  }
  return true;
}

bool Cut::crosses(const Vec3& a, const Vec3& b) const {
  const Vec3 n = normal();
  const double da = (a - origin).dot(n);
  const double db = (b - origin).dot(n);
  if ((da > 0 && db > 0) || (da < 0 && db < 0)) return false;
  if (da == db) return false;  // parallel to (or inside) the cut: does not cross it
  const Vec3 p = a + (b - a) * (da / (da - db));
  if (dim == 1) return true;
  // The cut is closed: a segment through its boundary crosses it. The
  // crossing point carries round-off, so s and t are compared with a margin
  // of kEdgeTie (in units of the edge lengths); without it, mirror-image bonds
  // through the edge would be decided by the last bit of p.
  constexpr double kEdgeTie = 1e-12;
  auto [s, t] = in_plane_coordinates(*this, p);
  if (s < -kEdgeTie || s > 1 + kEdgeTie) return false;
  if (dim == 2) return true;
  return t >= -kEdgeTie && t <= 1 + kEdgeTie && (!triangle || s + t <= 1 + 2 * kEdgeTie);
}

}  // namespace perimorph
