#include "perimorph/diagnostics/effective_gc.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/peridynamics/pair_kernel.hpp"
#include "perimorph/setup/discretization.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace perimorph::diagnostics {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string vec(const Vec3& v, int dim) {
  if (dim == 1) return fmt::format("({:.6g})", v.x());
  if (dim == 2) return fmt::format("({:.6g}, {:.6g})", v.x(), v.y());
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x(), v.y(), v.z());
}

/// Length of the line p + t u (u unit, in the xy plane) inside [lo, hi]:
/// Liang–Barsky clipping of t ∈ [−R, R], R larger than the box.
double clip_line(const Vec3& p, const Vec3& u, const Vec3& lo, const Vec3& hi, double R) {
  double t0 = -R, t1 = R;
  for (int i = 0; i < 2; ++i) {
    if (std::abs(u[i]) < 1e-300) {
      if (p[i] < lo[i] || p[i] > hi[i]) return 0.0;
      continue;
    }
    double a = (lo[i] - p[i]) / u[i], b = (hi[i] - p[i]) / u[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return std::max(0.0, t1 - t0);
}

/// Area of the polygon: a square of half-size R in the plane (centre p, unit
/// normal n), clipped against the six half-spaces of the box (Sutherland–Hodgman).
double clip_polygon(const Vec3& p, const Vec3& n, const Vec3& lo, const Vec3& hi, double R) {
  int k = 0;  // the axis least aligned with n
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[k])) k = i;
  Vec3 u = Vec3::Unit(k) - n * n[k];
  u.normalize();
  const Vec3 v = n.cross(u);
  std::vector<Vec3> poly{p - R * u - R * v, p + R * u - R * v, p + R * u + R * v, p - R * u + R * v};
  std::vector<Vec3> next;
  for (int i = 0; i < 3; ++i)
    for (const int side : {-1, 1}) {
      // Inside: side · (x_i − bound) ≤ 0.
      const double bound = side < 0 ? lo[i] : hi[i];
      auto f = [&](const Vec3& x) { return side * (x[i] - bound); };
      next.clear();
      for (std::size_t a = 0; a < poly.size(); ++a) {
        const Vec3& A = poly[a];
        const Vec3& B = poly[(a + 1) % poly.size()];
        const double fa = f(A), fb = f(B);
        if (fa <= 0) next.push_back(A);
        if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) next.push_back(A + (B - A) * (fa / (fa - fb)));
      }
      poly.swap(next);
      if (poly.size() < 3) return 0.0;
    }
  Vec3 twice = Vec3::Zero();
  for (std::size_t a = 0; a < poly.size(); ++a) twice += poly[a].cross(poly[(a + 1) % poly.size()]);
  return 0.5 * std::abs(twice.dot(n));
}

/// Side of a signed distance: −1, 0 (on the plane, within tol) or +1.
int side_of(double d, double tol) {
  return d > tol ? 1 : d < -tol ? -1 : 0;
}

/// Window weight of a crossing point: per axis 1 strictly inside [wlo, whi],
/// ½ on its border (within tol), 0 outside.
double window_weight(const Vec3& c, const Vec3& wlo, const Vec3& whi, int dim, double tol) {
  double w = 1.0;
  for (int i = 0; i < dim; ++i) {
    const double inside = std::min(c[i] - wlo[i], whi[i] - c[i]);
    if (inside < -tol) return 0.0;
    if (inside <= tol) w *= 0.5;
  }
  return w;
}

struct CellSums {
  double actual = 0.0, window = 0.0;
  std::size_t bonds = 0, window_bonds = 0, touching = 0, cut = 0, reduced_alpha = 0;
};

/// Bond sums over the cell pairs (E, F ≥ E) of the graph; per cell E, so the
/// total is summed in a fixed order (deterministic with threads).
template <int D>
std::vector<CellSums> sum_bonds(const setup::Discretization& model, const Vec3& point, const Vec3& n,
                                double s_crit, const Vec3& wlo, const Vec3& whi, bool has_window,
                                double tol) {
  const auto& nl = *model.nonlocal;
  const auto& pts = nl.points;
  PERIMORPH_ASSERT(pts.holds_every_cell(), "effective_gc reads every cell pair: it needs the whole model");
  const auto& cuts = model.mesh.cuts;
  const Index ncells = pts.num_cells();
  const int per = pts.per_cell;
  // Signed distances, and their range per cell to skip pairs on one side.
  std::vector<double> d(pts.x.size());
  std::vector<double> dmin(static_cast<std::size_t>(ncells)), dmax(static_cast<std::size_t>(ncells));
  for (Index c = 0; c < ncells; ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int q = 0; q < per; ++q) {
      const std::size_t k = pts.index(c, q);
      d[k] = (pts.x[k] - point).dot(n);
      lo = std::min(lo, d[k]);
      hi = std::max(hi, d[k]);
    }
    dmin[static_cast<std::size_t>(c)] = lo;
    dmax[static_cast<std::size_t>(c)] = hi;
  }
  const bool partial = pts.partial_volume();
  const double reach2 = peridynamics::bond_reach_squared(nl.kernel.horizon, partial, 2.0 * pts.half_bound);
  const double s2 = s_crit * s_crit;
  std::vector<CellSums> sums(static_cast<std::size_t>(ncells));
#pragma omp parallel for schedule(dynamic, 8)
  for (Index e = 0; e < ncells; ++e) {
    const std::size_t ue = static_cast<std::size_t>(e);
    CellSums s;
    for (const Index f : nl.graph.row(e)) {
      if (f < e) continue;  // unordered cell pairs, as the assembly
      const std::size_t uf = static_cast<std::size_t>(f);
      if (std::min(dmin[ue], dmin[uf]) > tol || std::max(dmax[ue], dmax[uf]) < -tol) continue;
      for (int g = 0; g < per; ++g) {
        const std::size_t kg = pts.index(e, g);
        const int sg = side_of(d[kg], tol);
        for (int h = e == f ? g + 1 : 0; h < per; ++h) {  // E = F: each unordered pair once
          const std::size_t kh = pts.index(f, h);
          const int sh = side_of(d[kh], tol);
          if (sg * sh == 1 || (sg == 0 && sh == 0)) continue;
          const double weight = sg * sh == -1 ? 1.0 : 0.5;
          const Vec3 xi = pts.x[kh] - pts.x[kg];
          const double r2 = xi.squaredNorm();
          if (!peridynamics::within_reach(r2, reach2)) continue;
          const double abar = 0.5 * (pts.alpha[kg] + pts.alpha[kh]);
          if (abar == 0.0) continue;
          const peridynamics::PairBond bond = peridynamics::pair_bond<D>(
              nl.kernel, pts.x[kg], pts.x[kh], xi, r2, partial ? &pts.half[kg] : nullptr,
              partial ? &pts.half[kh] : nullptr, cuts);
          s.cut += bond.cut ? 1 : 0;
          if (bond.c_bond == 0.0) continue;
          const double cb = bond.c_bond;
          // ½ ᾱ c_bond η² W with η = s_crit |ξ|.
          const double energy = 0.5 * abar * cb * s2 * r2 * pts.weight[kg] * pts.weight[kh] * weight;
          s.actual += energy;
          ++s.bonds;
          s.touching += weight < 1.0 ? 1 : 0;
          s.reduced_alpha += abar < 1.0 ? 1 : 0;
          if (!has_window) continue;
          const Vec3 crossing = sg == 0   ? pts.x[kg]
                                : sh == 0 ? pts.x[kh]
                                          : Vec3(pts.x[kg] + xi * (d[kg] / (d[kg] - d[kh])));
          const double w = window_weight(crossing, wlo, whi, D, tol);
          if (w == 0.0) continue;
          s.window += energy * w;
          ++s.window_bonds;
        }
      }
    }
    sums[ue] = s;
  }
  return sums;
}

}  // namespace

double section_measure(int dim, const Vec3& lo, const Vec3& hi, const CrackPlane& plane) {
  for (int i = 0; i < dim; ++i)
    if (!(lo[i] < hi[i])) return 0.0;
  const Vec3& p = plane.point;
  if (dim == 1) return p.x() > lo.x() && p.x() < hi.x() ? 1.0 : 0.0;
  Vec3 l = lo, u = hi;
  for (int i = dim; i < 3; ++i) l[i] = u[i] = 0.0;
  const Vec3 centre = 0.5 * (l + u);
  const Vec3& n = plane.normal;
  const Vec3 foot = centre - n * (centre - p).dot(n);  // the plane's point nearest the centre
  const double R = 2.0 * (u - l).norm();
  if (dim == 2) return clip_line(foot, Vec3(-n.y(), n.x(), 0.0), l, u, R);
  return clip_polygon(foot, n, l, u, R);
}

double PlaneSum::gc() const {
  return area > 0.0 ? energy / area : nan;
}

EffectiveGc effective_gc(const setup::Discretization& model, const CrackPlane& plane, double s_crit) {
  if (!model.nonlocal)
    throw InputError(
        fmt::format("{}: the case has no [nonlocal] section; G_c is a property of the bond "
                    "model (add [nonlocal])",
                    model.config.path));
  const int dim = model.dim();
  const auto& nl = *model.nonlocal;
  const auto [lo, hi] = model.mesh.bounding_box();
  double extent = 0.0;
  for (int i = 0; i < dim; ++i) extent = std::max(extent, hi[i] - lo[i]);
  const double tol = 1e-12 * extent;

  const double norm = plane.normal.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw InputError(
        fmt::format("--normal {} is not a direction; give the crack plane's normal, e.g. "
                    "--normal 0 1 0 for the plane y = const",
                    vec(plane.normal, 3)));
  const Vec3 n = plane.normal / norm;
  if (dim == 2 && std::abs(n.z()) > 1e-12)
    throw InputError(
        fmt::format("--normal {}: in 2D the crack plane is a line of the xy plane, so its "
                    "normal has no z component (e.g. --normal 0 1 0)",
                    vec(plane.normal, 3)));
  if (dim == 1 && (std::abs(n.y()) > 1e-12 || std::abs(n.z()) > 1e-12))
    throw InputError(
        fmt::format("--normal {}: in 1D the crack plane is the point x = X, normal to the "
                    "bar: give --normal 1 0 0",
                    vec(plane.normal, 3)));
  // The body must lie on both sides: some box corner strictly on each side.
  double dlo = std::numeric_limits<double>::infinity(), dhi = -dlo;
  for (int corner = 0; corner < (1 << dim); ++corner) {
    Vec3 x = Vec3::Zero();
    for (int i = 0; i < dim; ++i) x[i] = corner & (1 << i) ? hi[i] : lo[i];
    const double dc = (x - plane.point).dot(n);
    dlo = std::min(dlo, dc);
    dhi = std::max(dhi, dc);
  }
  if (!(dlo < -tol && dhi > tol))
    throw InputError(fmt::format(
        "the plane through {} with normal {} does not cut the body (box {} to {}){}; choose a point "
        "inside the box",
        vec(plane.point, dim), vec(n, dim), vec(lo, dim), vec(hi, dim),
        dlo >= -tol && dhi <= tol ? ""
        : dlo >= -tol             ? ": the whole box is on its positive side"
                                  : ": the whole box is on its negative side"));

  EffectiveGc r;
  r.plane = {plane.point, n};
  r.s_crit = s_crit;
  r.gc_factor = nl.calibration.gc_factor;
  r.closed_form = r.gc_factor * s_crit * s_crit;
  r.horizon = nl.kernel.horizon;
  // Areas: the measure of the section times the thickness (2D) or the
  // cross-section (1D), as the weights carry them.
  const double thickness = dim == 3 ? 1.0 : model.scale;
  r.actual.area = section_measure(dim, lo, hi, r.plane) * thickness;
  const Vec3 wlo = lo + Vec3::Constant(r.horizon), whi = hi - Vec3::Constant(r.horizon);
  r.window.area = section_measure(dim, wlo, whi, r.plane) * thickness;
  const bool has_window = r.window.area > 0.0;

  std::vector<CellSums> sums;
  switch (dim) {
    case 1:
      sums = sum_bonds<1>(model, plane.point, n, s_crit, wlo, whi, has_window, tol);
      break;
    case 2:
      sums = sum_bonds<2>(model, plane.point, n, s_crit, wlo, whi, has_window, tol);
      break;
    default:
      sums = sum_bonds<3>(model, plane.point, n, s_crit, wlo, whi, has_window, tol);
      break;
  }
  for (const auto& s : sums) {
    r.actual.energy += s.actual;
    r.actual.bonds += s.bonds;
    r.window.energy += s.window;
    r.window.bonds += s.window_bonds;
    r.touching += s.touching;
    r.cut += s.cut;
    r.reduced_alpha += s.reduced_alpha;
  }
  return r;
}

}  // namespace perimorph::diagnostics
