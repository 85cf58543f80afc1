#pragma once
// Test support: small cases built as typed CaseConfig structs (the form a
// parsed case file takes), so tests exercise the same path as the program.

#include "perimorph/casefile/case_config.hpp"

#include <limits>
#include <string>

namespace perimorph::testing {

/// Box of `cells` on [0, extent]^dim, one isotropic material, no loads.
inline casefile::CaseConfig box_case(int dim, std::array<Index, 3> cells, Vec3 extent, double E, double nu) {
  casefile::CaseConfig c;
  c.path = "test.toml";
  c.mesh.box = {dim, Vec3::Zero(), extent, cells};
  casefile::MaterialSpec m;
  m.name = "m";
  m.E = E;
  m.nu = nu;
  c.materials = {m};
  c.output.vtu = false;
  return c;
}

/// A [[dirichlet]] entry holding one component of a set at `value`.
inline casefile::DirichletSpec fixed(const std::string& set, int component, double value = 0.0) {
  casefile::DirichletSpec d;
  d.set = set;
  d.constrained[static_cast<std::size_t>(component)] = true;
  d.value[component] = value;
  return d;
}

/// Adds a [nonlocal] section.
inline void add_nonlocal(casefile::CaseConfig& c, casefile::KernelKind kernel, double horizon, double length,
                         int quadrature, casefile::Discretization dg = casefile::Discretization::continuous) {
  c.nonlocal.enabled = true;
  c.nonlocal.kernel = kernel;
  c.nonlocal.horizon = horizon;
  c.nonlocal.length = length;
  c.nonlocal.quadrature = quadrature;
  c.nonlocal.discretization = dg;
}

inline casefile::AlphaRegionSpec alpha_ball(Vec3 centre, double radius, double transition,
                                            casefile::AlphaProfile profile = casefile::AlphaProfile::cubic) {
  casefile::AlphaRegionSpec r;
  r.shape = casefile::AlphaShapeKind::ball;
  r.point = centre;
  r.radius = radius;
  r.transition = transition;
  r.profile = profile;
  return r;
}

/// A 2D hybrid plate (12 × 8 cells, constant kernel, δ = 1.2) with α ≡ 1 on a
/// disc of radius 3.5: DG where purely non-local, CG outside, so a partition of
/// it cuts both kinds of nodes. No loads or constraints.
inline casefile::CaseConfig mixed_cg_dg_plate() {
  auto c = box_case(2, {12, 8, 1}, Vec3(12.0, 8.0, 0.0), 100.0, 0.25);
  add_nonlocal(c, casefile::KernelKind::constant, 1.2, 0.0, 2, casefile::Discretization::discontinuous);
  c.alpha.regions = {alpha_ball(Vec3(6.0, 4.0, 0.0), 3.5, 1.0)};
  return c;
}

/// The message of the exception of type E that `f` throws ("" if none).
template <class E, class F>
std::string message_of_thrown(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace perimorph::testing
