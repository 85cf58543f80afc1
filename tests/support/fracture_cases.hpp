#pragma once
// Test support for the fracture tests: the pulled bar, plate and block of
// tests/evolution/fracture_test.cpp, the damage handover plate of
// tests/evolution/damage_test.cpp, and a reader of the run's numeric CSVs.

#include "perimorph/casefile/case_config.hpp"
#include "support/cases.hpp"

#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace perimorph::testing {

/// A bar [0, 20] (1D), a plate [0, 4] × [0, 2] (2D) or a block [0, 4] × [0, 2]
/// × [0, 1] (3D) pulled along x to
/// ε̄ = 1e-3 at load factor 1; non-local in the middle (cubic transition), the
/// discrete calibration so that the interior carries E ε exactly.
inline casefile::CaseConfig pulled_case(int dim, std::vector<double> factors, double s_crit) {
  casefile::CaseConfig c;
  if (dim == 1) {
    c = box_case(1, {160, 1, 1}, Vec3(20.0, 0, 0), 1.0, 0.0);
    add_nonlocal(c, casefile::KernelKind::constant, 0.5, 0.0, 3);
    casefile::AlphaRegionSpec r;
    r.shape = casefile::AlphaShapeKind::interval;
    r.lower = Vec3(7.0, 0, 0);
    r.upper = Vec3(13.0, 0, 0);
    r.transition = 2.0;
    c.alpha.regions = {r};
    c.dirichlet = {fixed("xmin", 0), fixed("xmax", 0, 0.02)};
  } else if (dim == 3) {
    c = box_case(3, {16, 8, 4}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
    add_nonlocal(c, casefile::KernelKind::gaussian, 0.75, 0.25, 2);
    casefile::AlphaRegionSpec r;
    r.shape = casefile::AlphaShapeKind::box;
    r.lower = Vec3(1.5, -1.0, -1.0);
    r.upper = Vec3(2.5, 3.0, 2.0);
    r.transition = 0.75;
    c.alpha.regions = {r};
    c.dirichlet = {fixed("xmin", 0), fixed("xmax", 0, 0.004)};
    casefile::NodeSetSpec corner, edge;
    corner.name = "origin";
    edge.name = "yedge";  // (0, 2, 0): stops the rotation about x
    edge.lower = edge.upper = Vec3(0.0, 2.0, 0.0);
    c.node_sets = {corner, edge};
    c.dirichlet.push_back(fixed("origin", 1));
    c.dirichlet.push_back(fixed("origin", 2));
    c.dirichlet.push_back(fixed("yedge", 2));
  } else {
    c = box_case(2, {32, 16, 1}, Vec3(4.0, 2.0, 1.0), 1.0, 0.25);
    add_nonlocal(c, casefile::KernelKind::gaussian, 0.375, 0.125, 3);
    casefile::AlphaRegionSpec r;
    r.shape = casefile::AlphaShapeKind::box;
    r.lower = Vec3(1.5, -1.0, 0);
    r.upper = Vec3(2.5, 3.0, 0);
    r.transition = 0.75;
    c.alpha.regions = {r};
    c.dirichlet = {fixed("xmin", 0), fixed("xmax", 0, 0.004)};
    casefile::NodeSetSpec corner;
    corner.name = "origin";
    c.node_sets = {corner};
    c.dirichlet.push_back(fixed("origin", 1));
  }
  c.materials[0].nu = std::numeric_limits<double>::quiet_NaN();
  c.nonlocal.calibration = casefile::CalibrationRule::discrete;
  c.loading.factors = std::move(factors);
  c.fracture.enabled = true;
  c.fracture.s_crit = s_crit;
  c.solver.rtol = 1e-12;
  return c;
}

/// The plate of pulled_case (2D, gaussian kernel δ = 3h, DG where purely
/// non-local) with a hole at its centre, α ≡ 0 at the start, damage d_c = 0.2
/// handing over to the non-local model ([adaptivity]), bonds failing at s_crit.
inline casefile::CaseConfig handover_plate(int increments) {
  auto c = pulled_case(2, {}, 2.5e-3);
  c.alpha.regions.clear();
  c.nonlocal.discretization = casefile::Discretization::discontinuous;
  c.nonlocal.calibration = casefile::CalibrationRule::continuum;  // the hole: no structured grid
  casefile::HoleSpec hole;
  hole.shape = HoleShape::disk;
  hole.center = Vec3(2.0, 1.0, 0.0);
  hole.radius = 0.3;
  c.mesh.holes = {hole};
  // Y far from the hole ≈ 6e-7 at λ = 1 (E = 1, ε̄ = 1e-3).
  auto& d = c.materials[0].damage;
  d.enabled = true;
  d.k0 = 3e-7;
  d.k1 = 3e-6;
  d.d_c = 0.2;
  c.adaptivity.enabled = true;
  c.output.failed_bonds = true;
  for (int i = 1; i <= increments; ++i) c.loading.factors.push_back(1.2 * i / increments);
  c.solver.rtol = 1e-10;
  c.solver.petsc_options = "-ksp_type preonly -pc_type cholesky";
  c.damage.tolerance = 1e-4;  // (CI time: the default 1e-6 takes ~4x the fixed-point iterations)
  return c;
}

/// Rows of a numeric CSV written by io::CsvTable, by column name.
inline std::vector<std::map<std::string, double>> read_rows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream ss(line); std::getline(ss, line, ',');) names.push_back(line);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, double> row;
    std::stringstream ss(line);
    for (const auto& n : names) {
      std::string v;
      std::getline(ss, v, ',');
      row[n] = std::stod(v);
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace perimorph::testing
