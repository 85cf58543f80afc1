#pragma once
// The B6 geometry of the benchmarks (BENCHMARKS.md B6): block 12δ × 8δ × 2δ,
// δ = 1, gaussian kernel l = δ/3, E = 300 GPa, ν = 1/4, pre-crack cut in the
// plane y = 4 for x < 4, α = 1 in the box x ≥ 3, 3 ≤ y ≤ 5 (all z) with a
// cubic transition 1.5 wide, DG where purely non-local, 2×2×2 non-local
// points per cell; opened by u = (0, ±u_d, 0) on the top and bottom faces
// for x ≤ 2 (all components prescribed there), u_d = 0.01.

#include "perimorph/casefile/case_config.hpp"

#include <fmt/format.h>

#include <limits>
#include <string>

namespace perimorph::bench {

constexpr double kOpening = 0.01;  // u_d

inline casefile::DirichletSpec opening(const std::string& set, double uy) {
  casefile::DirichletSpec d;
  d.set = set;
  d.constrained = {true, true, true};
  d.value = Vec3(0.0, uy, 0.0);
  return d;
}

inline casefile::NodeSetSpec node_set(const std::string& name, Vec3 lower, Vec3 upper) {
  casefile::NodeSetSpec s;
  s.name = name;
  s.lower = lower;
  s.upper = upper;
  return s;
}

/// B6 with nx × (2nx/3) × (nx/6) cells.
inline casefile::CaseConfig b6_case(int nx) {
  const double inf = std::numeric_limits<double>::infinity();
  casefile::CaseConfig c;
  c.path = fmt::format("b6_nx{}.toml", nx);
  c.mesh.box = {3, Vec3::Zero(), Vec3(12.0, 8.0, 2.0), {nx, nx * 8 / 12, nx * 2 / 12}};
  casefile::CutSpec cut;
  cut.origin = Vec3(0.0, 4.0, 0.0);
  cut.edge1 = Vec3(4.0, 0.0, 0.0);
  cut.edge2 = Vec3(0.0, 0.0, 2.0);
  c.mesh.cuts = {cut};
  auto& m = c.materials.emplace_back();
  m.name = std::string(1, 'm');  // not from a literal: GCC 12's -Wrestrict false positive
  m.E = 300e9;
  m.nu = 0.25;
  c.nonlocal.enabled = true;
  c.nonlocal.kernel = casefile::KernelKind::gaussian;
  c.nonlocal.horizon = 1.0;
  c.nonlocal.length = 1.0 / 3.0;
  c.nonlocal.quadrature = 2;
  c.nonlocal.discretization = casefile::Discretization::discontinuous;
  casefile::AlphaRegionSpec r;
  r.shape = casefile::AlphaShapeKind::box;
  r.lower = Vec3(3.0, 3.0, -inf);
  r.upper = Vec3(inf, 5.0, inf);
  r.transition = 1.5;
  r.profile = casefile::AlphaProfile::cubic;
  c.alpha.regions = {r};
  c.node_sets = {node_set("top_left", Vec3(0.0, 8.0, 0.0), Vec3(2.0, 8.0, 2.0)),
                 node_set("bottom_left", Vec3(0.0, 0.0, 0.0), Vec3(2.0, 0.0, 2.0))};
  c.dirichlet = {opening("top_left", kOpening), opening("bottom_left", -kOpening)};
  c.fracture.enabled = true;
  c.fracture.s_crit = 1.0;  // set per benchmark
  c.output.vtu = false;
  return c;
}

}  // namespace perimorph::bench
