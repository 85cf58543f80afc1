// The critical energy release rate of a crack plane (diagnostics/effective_gc.hpp,
// THEORY §5): the section areas of a box, the bulk window against the closed
// form under refinement (h → h/2 at fixed δ) in 1D, 2D and 3D, the lower value
// of the actual geometry near free faces, pre-crack cuts, the tie rule, units
// and scalings, the choice of s_crit and the messages for bad planes. The
// refinement table is docs/verification/effective-gc.md.

#include "perimorph/diagnostics/effective_gc.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/setup/discretization.hpp"
#include "support/cases.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace perimorph {
namespace {

using casefile::HorizonEdge;
using casefile::KernelKind;
using diagnostics::CrackPlane;

constexpr double delta = 1.0;

/// A fully non-local (α ≡ 1) box [0, extent]^dim with m cells per δ, E = 1,
/// 2 non-local points per direction, l = δ/5 for the exponential kernel.
casefile::CaseConfig block(int dim, int m, double extent, KernelKind kernel,
                           HorizonEdge edge = HorizonEdge::cutoff, int quadrature = 2) {
  const Index n = static_cast<Index>(std::lround(extent * m / delta));
  auto c = testing::box_case(dim, {n, dim > 1 ? n : 1, dim > 2 ? n : 1}, Vec3::Constant(extent), 1.0, 0.25);
  testing::add_nonlocal(c, kernel, delta, delta / 5, quadrature);
  c.nonlocal.horizon_edge = edge;
  c.alpha.value = 1.0;
  return c;
}

/// The plane normal to the last axis through the box's centre.
CrackPlane mid_plane(int dim, double extent) {
  return {Vec3::Constant(extent / 2), Vec3::Unit(dim - 1)};
}

diagnostics::EffectiveGc gc_of(const casefile::CaseConfig& c, const CrackPlane& p, double s_crit = 1.0) {
  return diagnostics::effective_gc(setup::build_discretization(c), p, s_crit);
}

const char* kernel_name(KernelKind k) {
  return k == KernelKind::constant ? "constant" : k == KernelKind::conical ? "conical" : "exponential l=δ/5";
}

TEST(EffectiveGc, SectionMeasureOfABox) {
  const Vec3 lo = Vec3::Zero(), hi = Vec3::Ones();
  const double s3 = std::sqrt(3.0);
  auto measure = [&](int dim, Vec3 point, Vec3 normal) {
    return diagnostics::section_measure(dim, lo, hi, {point, normal.normalized()});
  };
  EXPECT_NEAR(measure(3, Vec3(0.3, 0, 0), Vec3::UnitX()), 1.0, 1e-14);
  // x + y + z = 3/2: the regular hexagon of side √2/2; x + y + z = 1/2: a triangle of side √2/2.
  EXPECT_NEAR(measure(3, Vec3::Constant(0.5), Vec3::Ones()), 3.0 * s3 / 4.0, 1e-14);
  EXPECT_NEAR(measure(3, Vec3(0.5, 0, 0), Vec3::Ones()), s3 / 8.0, 1e-14);
  EXPECT_NEAR(measure(3, Vec3(0.5, 0.5, 0.5), Vec3(1, 1, 0)), std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(measure(3, Vec3(2, 0, 0), Vec3::Ones()), s3 / 2.0, 1e-14);  // the triangle at (1, 1, 1)
  EXPECT_EQ(measure(3, Vec3(4, 0, 0), Vec3::Ones()), 0.0);
  EXPECT_NEAR(measure(2, Vec3(0.5, 0.5, 7), Vec3(1, 1, 0)), std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(measure(2, Vec3(0, 0.25, 0), Vec3::UnitY()), 1.0, 1e-14);
  EXPECT_NEAR(measure(2, Vec3(0.25, 0, 0), Vec3(1, 1, 0)), std::sqrt(2.0) / 4.0, 1e-14);
  EXPECT_EQ(measure(2, Vec3(3, 0, 0), Vec3(1, 1, 0)), 0.0);
  EXPECT_EQ(measure(1, Vec3(0.5, 0, 0), Vec3::UnitX()), 1.0);
  EXPECT_EQ(measure(1, Vec3(1.5, 0, 0), Vec3::UnitX()), 0.0);
  // An empty box (the window of a body thinner than 2δ).
  EXPECT_EQ(diagnostics::section_measure(3, Vec3::Constant(0.6), Vec3::Constant(0.4),
                                         {Vec3::Zero(), Vec3::UnitX()}),
            0.0);
}

/// One refinement series: the measured error of its finest level (the bound
/// is 1.5 times it), whether every step must decrease the error, and the
/// least observed order of the last step (0: not asserted).
struct Series {
  int dim;
  KernelKind kernel;
  HorizonEdge edge;
  double measured;
  bool every_step;
  double min_order;
};

// Bulk window vs the closed form κ s_crit²: h = δ/m, m doubling, δ fixed. The
// error is the quadrature error of the bond sum (the kernel scale is the
// continuum calibration). Cut-off edges with a kernel that does not vanish at
// δ (constant, exponential) converge like h, with lattice noise in 2D (the
// m = 4 → 8 step of the 2D constant kernel increases the error); the partial
// volume edge and the conical kernel converge like h².
TEST(EffectiveGc, BulkWindowConvergesToTheClosedForm) {
  const std::vector<Series> series = {
      {1, KernelKind::constant, HorizonEdge::cutoff, 3.108e-2, true, 0.9},
      {1, KernelKind::constant, HorizonEdge::partial_volume, 1.280e-4, true, 1.8},
      {1, KernelKind::conical, HorizonEdge::cutoff, 4.362e-4, true, 1.8},
      {1, KernelKind::conical, HorizonEdge::partial_volume, 3.715e-4, true, 1.8},
      {1, KernelKind::exponential, HorizonEdge::cutoff, 1.790e-2, true, 0.9},
      {1, KernelKind::exponential, HorizonEdge::partial_volume, 5.602e-5, true, 1.8},
      {2, KernelKind::constant, HorizonEdge::cutoff, 5.623e-3, false, 0.0},
      {2, KernelKind::constant, HorizonEdge::partial_volume, 6.981e-4, true, 1.6},
      {2, KernelKind::conical, HorizonEdge::cutoff, 1.467e-4, true, 1.8},
      {2, KernelKind::conical, HorizonEdge::partial_volume, 2.321e-3, true, 1.6},
      {2, KernelKind::exponential, HorizonEdge::cutoff, 3.502e-3, false, 0.0},
      {2, KernelKind::exponential, HorizonEdge::partial_volume, 3.032e-4, true, 1.6},
      {3, KernelKind::constant, HorizonEdge::cutoff, 1.073e-2, true, 0.0},
      {3, KernelKind::constant, HorizonEdge::partial_volume, 8.374e-3, true, 1.6},
      {3, KernelKind::conical, HorizonEdge::cutoff, 2.332e-4, true, 1.6},
      {3, KernelKind::conical, HorizonEdge::partial_volume, 4.570e-2, true, 1.5},
      {3, KernelKind::exponential, HorizonEdge::cutoff, 6.972e-3, true, 0.0},
      {3, KernelKind::exponential, HorizonEdge::partial_volume, 8.640e-3, true, 1.6},
  };
  std::printf("| dim | kernel | edge | δ/h | window / closed − 1 | order | actual / closed | bonds |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const auto& s : series) {
    // Box edge 4δ (3δ in 3D): the window is the middle half (third) of the plane.
    const double extent = s.dim == 3 ? 3.0 : 4.0;
    const std::vector<int> levels = s.dim == 1   ? std::vector<int>{4, 8, 16, 32}
                                    : s.dim == 2 ? std::vector<int>{4, 8, 16}
                                                 : std::vector<int>{2, 4};
    std::vector<double> errors;
    for (const int m : levels) {
      const auto g = gc_of(block(s.dim, m, extent, s.kernel, s.edge), mid_plane(s.dim, extent));
      const double rel = g.window.gc() / g.closed_form - 1.0;
      errors.push_back(std::abs(rel));
      const double order = errors.size() > 1 ? std::log2(errors[errors.size() - 2] / errors.back())
                                             : std::numeric_limits<double>::quiet_NaN();
      char order_text[16] = "";
      if (!std::isnan(order)) std::snprintf(order_text, sizeof order_text, "%.2f", order);
      std::printf("| %d | %s | %s | %d | %+.3e | %s | %.4f | %zu |\n", s.dim, kernel_name(s.kernel),
                  s.edge == HorizonEdge::cutoff ? "cut-off" : "partial volume", m, rel, order_text,
                  g.actual.gc() / g.closed_form, g.actual.bonds);
    }
    const std::string what = std::to_string(s.dim) + "D " + kernel_name(s.kernel) +
                             (s.edge == HorizonEdge::cutoff ? " cut-off" : " partial volume");
    EXPECT_LT(errors.back(), 1.5 * s.measured) << what;
    EXPECT_LT(errors.back(), 0.5 * errors.front()) << what;
    if (s.every_step) {
      for (std::size_t k = 1; k < errors.size(); ++k)
        EXPECT_LT(errors[k], errors[k - 1]) << what << " step " << k;
    }
    if (s.min_order > 0) {
      EXPECT_GT(std::log2(errors[errors.size() - 2] / errors.back()), s.min_order) << what;
    }
  }
}

// Free faces: the horizons of bonds crossing near a face are incomplete, so
// the actual value is below the bulk one. The deficit is a property of each
// face: lengthening the plane by 2δ (a 6δ-wide instead of 4δ-wide plate)
// leaves it unchanged. Continuum value (2D, plane y = 0, face x = 0): a bond ξ
// (ξ_y > 0) crossing at distance x_c from the face, at the fraction τ of its
// length, has its lower end outside iff x_c < τ ξ_x (ξ_x > 0); integrating
// over x_c and τ, D = ¼ ∫_{ξ_y > 0} c |ξ|² ξ_y |ξ_x| dξ = ¼ ∫₀^δ c r⁵ dr (the
// angular integral ∫₀^π sin θ |cos θ| dθ is 1) per unit thickness, against
// G = ∫₀^δ c r⁴ dr: D = 5δ/24 G for the constant kernel.
TEST(EffectiveGc, FreeFacesLowerTheActualValue) {
  const int m = 4;
  double deficit[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const double width = k == 0 ? 4.0 : 6.0;
    auto c = block(2, m, 4.0, KernelKind::constant, HorizonEdge::partial_volume);
    c.mesh.box.upper.x() = width;
    c.mesh.box.cells[0] = static_cast<Index>(width * m);
    const auto g = gc_of(c, {Vec3(width / 2, 2.0, 0), Vec3::UnitY()});
    EXPECT_LT(g.actual.gc(), 0.95 * g.window.gc());
    EXPECT_NEAR(g.window.area, width - 2 * delta, 1e-12);
    EXPECT_NEAR(g.actual.area, width, 1e-12);
    // Per face: the bulk value over the whole plane minus what the plane holds.
    deficit[k] = 0.5 * (g.window.gc() * g.actual.area - g.actual.energy);
    std::printf(
        "2D plate %g x 4: actual / window = %.5f, deficit per face = %.6e = %.5f delta G_window "
        "(continuum 5/24 = %.5f)\n",
        width, g.actual.gc() / g.window.gc(), deficit[k], deficit[k] / g.window.gc(), 5.0 / 24.0);
    // Measured 0.20995 (+0.8 %).
    EXPECT_NEAR(deficit[k] / (delta * g.window.gc()), 5.0 / 24.0, 0.02 * 5.0 / 24.0);
  }
  EXPECT_NEAR(deficit[1], deficit[0], 1e-9 * deficit[0]);
  // 3D: four lateral faces and four corners, E = G Lx Ly − 2 D (Lx + Ly) + K;
  // lengthening Lx by 2δ gives D. Continuum: D = ¼ ∫ c r⁶ dr ∫_{hemisphere}
  // cos θ |sin θ cos φ| dΩ = ⅓ ∫ c r⁶ dr, against G = π/2 ∫ c r⁵ dr:
  // D = δ G / (2π) for the conical kernel.
  double energy[2], bulk[2];
  for (int k = 0; k < 2; ++k) {
    const double lx = k == 0 ? 3.0 : 5.0;
    auto c = block(3, m, 3.0, KernelKind::conical);
    c.mesh.box.upper.x() = lx;
    c.mesh.box.cells[0] = static_cast<Index>(lx * m);
    const auto g = gc_of(c, {Vec3(lx / 2, 1.5, 1.5), Vec3::UnitZ()});
    EXPECT_LT(g.actual.gc(), 0.85 * g.window.gc());
    energy[k] = g.actual.energy;
    bulk[k] = g.window.gc();
    std::printf("3D block %g x 3 x 3: actual / window = %.5f\n", lx, g.actual.gc() / g.window.gc());
  }
  const double d3 = (bulk[1] * 3.0 * 2.0 * delta - (energy[1] - energy[0])) / (4.0 * delta);
  std::printf("3D deficit per unit edge length = %.5f delta G_window (continuum 1/(2 pi) = %.5f)\n",
              d3 / (delta * bulk[1]), 0.5 / std::numbers::pi);
  EXPECT_NEAR(bulk[1], bulk[0], 1e-12 * bulk[0]);
  // Measured 0.15936 (+0.13 %).
  EXPECT_NEAR(d3 / (delta * bulk[1]), 0.5 / std::numbers::pi, 0.01 * 0.5 / std::numbers::pi);
}

// 1D: no lateral faces, so a plane farther than δ from both ends of the bar is
// all window; within δ of an end there is no window and the value drops.
TEST(EffectiveGc, OneDimensionalBarHasNoLateralFaces) {
  const auto c = block(1, 8, 4.0, KernelKind::constant);
  const auto model = setup::build_discretization(c);
  const auto far = diagnostics::effective_gc(model, {Vec3(1.7, 0, 0), Vec3::UnitX()}, 1.0);
  EXPECT_EQ(far.window.bonds, far.actual.bonds);
  EXPECT_NEAR(far.window.gc(), far.actual.gc(), 1e-14 * far.actual.gc());
  const auto near = diagnostics::effective_gc(model, {Vec3(0.5, 0, 0), Vec3::UnitX()}, 1.0);
  EXPECT_EQ(near.window.area, 0.0);
  EXPECT_TRUE(std::isnan(near.window.gc()));
  EXPECT_LT(near.actual.gc(), 0.8 * far.actual.gc());
}

// A pre-crack in the plane: the bonds crossing it are left out. A cut over
// the whole plane leaves nothing; a cut over either half leaves a bit less than
// half: the bonds crossing the plane exactly at the cut's end (mirror pairs
// about the cell face x = 2) touch the cut. Whether round-off puts such a
// crossing a hair inside or outside the cut is Cut::crosses' business
// (the assembly uses the same test), so the two halves differ slightly and the
// bonds through the common end may be cut by both.
TEST(EffectiveGc, PreCrackCutRemovesItsBonds) {
  auto with_cut = [](double x0, double x1) {
    auto c = block(2, 4, 4.0, KernelKind::constant);
    if (x1 > x0) {
      casefile::CutSpec cut;
      cut.origin = Vec3(x0, 2.0, 0);
      cut.edge1 = Vec3(x1 - x0, 0, 0);
      c.mesh.cuts.push_back(cut);
    }
    return gc_of(c, mid_plane(2, 4.0));
  };
  const auto none = with_cut(0, 0), all = with_cut(0, 4), left = with_cut(0, 2), right = with_cut(2, 4);
  EXPECT_EQ(none.cut, 0u);
  EXPECT_EQ(all.actual.bonds, 0u);
  EXPECT_EQ(all.actual.energy, 0.0);
  EXPECT_EQ(all.cut, none.actual.bonds);
  EXPECT_EQ(all.window.energy, 0.0);
  for (const auto* half : {&left, &right}) {
    EXPECT_EQ(half->actual.bonds + half->cut, none.actual.bonds);
    EXPECT_LT(half->actual.energy, 0.5 * none.actual.energy);
    EXPECT_GT(half->actual.energy, 0.49 * none.actual.energy);
  }
  const double shared = none.actual.energy - left.actual.energy - right.actual.energy;
  std::printf("a cut over the left (right) half of the plane keeps %.5f (%.5f) of its energy\n",
              left.actual.energy / none.actual.energy, right.actual.energy / none.actual.energy);
  EXPECT_GT(shared, 0.0);
  EXPECT_LT(shared, 0.01 * none.actual.energy);
}

// Ties: with 3 points per direction a row of points lies on the plane y = 2.125
// (the centres of a row of cells); bonds from them count ½, the mean of the
// plane moved by ±ε.
TEST(EffectiveGc, PointsOnThePlaneCountHalf) {
  const auto model =
      setup::build_discretization(block(2, 4, 4.0, KernelKind::constant, HorizonEdge::cutoff, 3));
  const double y = 2.125, eps = 1e-6;
  const auto on = diagnostics::effective_gc(model, {Vec3(2, y, 0), Vec3::UnitY()}, 1.0);
  const auto above = diagnostics::effective_gc(model, {Vec3(2, y + eps, 0), Vec3::UnitY()}, 1.0);
  const auto below = diagnostics::effective_gc(model, {Vec3(2, y - eps, 0), Vec3::UnitY()}, 1.0);
  EXPECT_GT(on.touching, 0u);
  EXPECT_EQ(above.touching, 0u);
  EXPECT_NE(above.actual.energy, below.actual.energy);
  EXPECT_NEAR(on.actual.energy, 0.5 * (above.actual.energy + below.actual.energy), 1e-13 * on.actual.energy);
  EXPECT_NEAR(on.window.energy, 0.5 * (above.window.energy + below.window.energy), 1e-13 * on.window.energy);
}

// Oblique planes (normal (1, 2) in 2D, (1, 2, 3) in 3D, through the centre):
// the window is a segment of length √5 in 2D, a polygon in 3D, and the crossing
// points are interpolated along the bonds. With the conical kernel (h = δ/8 in
// 2D, δ/4 in 3D) the window matches the closed form as closely as the
// axis-aligned plane does: measured −1.3e-3 and −8.7e-4 (axis-aligned: −6.7e-4
// and −2.3e-4).
TEST(EffectiveGc, ObliquePlanes) {
  for (const int dim : {2, 3}) {
    const double extent = dim == 2 ? 4.0 : 3.0;
    const auto c = block(dim, dim == 2 ? 8 : 4, extent, KernelKind::conical);
    const Vec3 n = dim == 2 ? Vec3(1, 2, 0) : Vec3(1, 2, 3);
    const auto g = gc_of(c, {Vec3::Constant(extent / 2), n});
    std::printf("%dD oblique plane: window / closed - 1 = %+.3e, actual / closed = %.4f, window area %.4f\n",
                dim, g.window.gc() / g.closed_form - 1, g.actual.gc() / g.closed_form, g.window.area);
    EXPECT_NEAR(g.plane.normal.norm(), 1.0, 1e-15);
    if (dim == 2) {
      EXPECT_NEAR(g.window.area, std::sqrt(5.0), 1e-13);
    }
    EXPECT_NEAR(g.window.gc() / g.closed_form, 1.0, 3e-3);
    EXPECT_LT(g.actual.gc(), g.window.gc());
  }
}

// Units: in 2D the value does not depend on the thickness, in 1D not on the
// cross-section; it scales with s_crit² and with ᾱ.
TEST(EffectiveGc, IndependentOfThicknessAndScalesWithStretchAndAlpha) {
  for (const int dim : {1, 2}) {
    auto c = block(dim, 4, 4.0, KernelKind::exponential);
    const auto ref = gc_of(c, mid_plane(dim, 4.0));
    c.model.thickness = 0.3;
    const auto thin = gc_of(c, mid_plane(dim, 4.0), 2e-3);
    EXPECT_NEAR(thin.actual.area, 0.3 * ref.actual.area, 1e-14);
    EXPECT_NEAR(thin.actual.gc(), 4e-6 * ref.actual.gc(), 1e-12 * 4e-6 * ref.actual.gc()) << dim << "D";
    EXPECT_NEAR(thin.window.gc(), 4e-6 * ref.window.gc(), 1e-12 * 4e-6 * ref.window.gc()) << dim << "D";
    EXPECT_NEAR(thin.closed_form, 4e-6 * ref.closed_form, 1e-12 * ref.closed_form);
    c.alpha.value = 0.5;
    const auto half = gc_of(c, mid_plane(dim, 4.0));
    EXPECT_NEAR(half.actual.gc(), 0.5 * ref.actual.gc(), 1e-12 * ref.actual.gc()) << dim << "D";
    EXPECT_EQ(ref.reduced_alpha, 0u);
    EXPECT_EQ(half.reduced_alpha, half.actual.bonds);
  }
}

/// The bulk G_c of an anisotropic kernel c_r(r) Y(e) for the plane of unit
/// normal n, integrated here: ½ s² ∫₀^δ c_r r⁵ dr ∫_{e·n > 0} Y(e) e·n dΩ
/// (the 3D row of THEORY §5 with the angular factor kept under the integral;
/// Y ≡ 1 gives π/2). Gauss in cos θ about n, trapezoid in φ: exact for the
/// degree-4 polynomial Y.
double anisotropic_bulk_gc(const peridynamics::Micromodulus& c, const Vec3& n) {
  const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  const int nphi = 32;
  double angular = 0.0;
  for (const auto& q : fem::gauss_legendre_1d(8)) {
    const double t = 0.5 * (q.xi.x() + 1.0), st = std::sqrt(1.0 - t * t);  // t = cos θ on [0, 1]
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / nphi;
      const Vec3 e = t * n + st * (std::cos(phi) * u + std::sin(phi) * v);
      angular += 0.5 * q.weight * (2.0 * std::numbers::pi / nphi) * c.angular(e, 1.0) * t;
    }
  }
  return 0.5 * c.moment(5) * angular;
}

// An anisotropic (orthotropic, E3 = 2.5 E1) kernel: no closed form is
// reported, but the bond sums are, and the bulk window matches the integral of
// the anisotropic kernel over the plane (computed above) within the
// quadrature error of the isotropic case; the planes normal to e1 and e3 differ.
TEST(EffectiveGc, AnisotropicKernelDependsOnThePlane) {
  auto c = block(3, 4, 3.0, KernelKind::exponential);
  {  // The integral reproduces κ for an isotropic kernel.
    auto iso = c;
    iso.mesh.box.cells = {2, 2, 2};
    const auto model = setup::build_discretization(iso);
    EXPECT_NEAR(anisotropic_bulk_gc(model.nonlocal->kernel, Vec3(1, 2, 2) / 3.0),
                model.nonlocal->calibration.gc_factor, 1e-13 * model.nonlocal->calibration.gc_factor);
  }
  auto& m = c.materials.front();
  m.kind = casefile::MaterialKind::orthotropic;
  m.E1 = 60e3;
  m.E2 = 90e3;
  m.E3 = 150e3;
  m.nu12 = 0.3;
  m.nu13 = 0.1;
  m.nu23 = 0.2;
  m.G12 = m.G13 = m.G23 = std::numeric_limits<double>::quiet_NaN();
  const auto model = setup::build_discretization(c);
  double window[3];
  for (int axis : {0, 2}) {
    const Vec3 n = Vec3::Unit(axis);
    const auto g = diagnostics::effective_gc(model, {Vec3::Constant(1.5), n}, 1.0);
    EXPECT_TRUE(std::isnan(g.closed_form));
    const double bulk = anisotropic_bulk_gc(model.nonlocal->kernel, n);
    window[axis] = g.window.gc();
    std::printf("orthotropic, plane normal to e%d: window / integral - 1 = %+.3e, actual / integral = %.4f\n",
                axis + 1, g.window.gc() / bulk - 1, g.actual.gc() / bulk);
    // Measured +1.30e-2 (e1) and -4.8e-3 (e3); the isotropic kernel at this h: +7.0e-3.
    EXPECT_NEAR(g.window.gc() / bulk, 1.0, 2.5e-2);
    EXPECT_LT(g.actual.gc(), g.window.gc());
  }
  EXPECT_GT(window[2], 1.2 * window[0]);
}

TEST(EffectiveGc, BadPlanesSayWhatToChange) {
  const auto m3 = setup::build_discretization(block(3, 2, 3.0, KernelKind::constant));
  const auto m2 = setup::build_discretization(block(2, 2, 4.0, KernelKind::constant));
  const auto m1 = setup::build_discretization(block(1, 2, 4.0, KernelKind::constant));
  auto msg = [](const setup::Discretization& m, Vec3 p, Vec3 n) {
    return testing::message_of_thrown<InputError>([&] { diagnostics::effective_gc(m, {p, n}, 1.0); });
  };
  EXPECT_NE(msg(m3, Vec3::Ones(), Vec3::Zero()).find("is not a direction"), std::string::npos);
  EXPECT_NE(msg(m3, Vec3(5, 0, 0), Vec3::UnitX()).find("does not cut the body"), std::string::npos);
  EXPECT_NE(msg(m3, Vec3(5, 0, 0), Vec3::UnitX()).find("negative side"), std::string::npos);
  // A plane on a face cuts no bond.
  EXPECT_NE(msg(m3, Vec3::Zero(), Vec3::UnitX()).find("does not cut the body"), std::string::npos);
  EXPECT_NE(msg(m2, Vec3::Ones(), Vec3(0, 1, 1)).find("no z component"), std::string::npos);
  EXPECT_NE(msg(m1, Vec3::Ones(), Vec3(1, 1, 0)).find("--normal 1 0 0"), std::string::npos);
  auto local = testing::box_case(2, {2, 2, 1}, Vec3::Ones(), 1.0, 0.3);
  const auto ml = setup::build_discretization(local);
  EXPECT_NE(msg(ml, Vec3::Constant(0.5), Vec3::UnitX()).find("[nonlocal]"), std::string::npos);
}

}  // namespace
}  // namespace perimorph
