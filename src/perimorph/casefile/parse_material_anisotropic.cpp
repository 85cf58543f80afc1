// Case-file parsing of the anisotropic [[material]] types: orthotropic
// (engineering constants or stiffness components) and transversely isotropic
// materials, and material axes (`rotation`). Called by read_material
// (parse_material.cpp); same conventions. Only the input is checked here
// (ranges, stability).

#include "perimorph/casefile/parse_material_detail.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace perimorph::casefile::detail::material {

namespace {

/// A shear modulus or shear stiffness component: positive when given, NaN
/// when left out (only with [nonlocal]).
double read_shear(const Table& t, const std::string& key, bool nonlocal, std::string_view what,
                  std::string_view form) {
  const std::string needs = fmt::format(
      "the {} {} is required (shear values may only be left out {}); an orthotropic material needs {}", what,
      key, kCentralForces, form);
  const std::optional<Value> v = optional_in_nonlocal(t, key, nonlocal, needs);
  return v ? positive(*v, fmt::format("a {}", what)) : kNaN;
}

/// Fails unless the compliance of E1..E3, nu12, nu13, nu23 (normal block) is
/// positive definite, by Sylvester's criterion: nu_ij^2 < E_i / E_j, and
/// det S > 0.
void check_compliance(const Table& t, const MaterialSpec& m) {
  const double E[3] = {m.E1, m.E2, m.E3};
  const struct {
    int i, j;
    double nu;
    const char* key;
  } pairs[3] = {{0, 1, m.nu12, "nu12"}, {0, 2, m.nu13, "nu13"}, {1, 2, m.nu23, "nu23"}};
  for (const auto& p : pairs)
    if (!(p.nu * p.nu < E[p.i] / E[p.j]))
      t.get(p.key)->fail(
          fmt::format("{} = {} needs |{}| < sqrt(E{} / E{}) = {:.4g} for a positive-definite compliance (a "
                      "stable material)",
                      p.key, p.nu, p.key, p.i + 1, p.j + 1, std::sqrt(E[p.i] / E[p.j])));
  const double nu21 = m.nu12 * m.E2 / m.E1, nu31 = m.nu13 * m.E3 / m.E1, nu32 = m.nu23 * m.E3 / m.E2;
  const double det = 1 - m.nu12 * nu21 - m.nu23 * nu32 - m.nu13 * nu31 - 2 * nu21 * nu32 * m.nu13;
  if (!(det > 0))
    t.fail(fmt::format(
        "the Poisson ratios nu12 = {}, nu13 = {}, nu23 = {} make the compliance indefinite (an "
        "unstable material): 1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 nu32 nu13 = {:.4g} must be "
        "positive",
        m.nu12, m.nu13, m.nu23, det));
}

void read_engineering(const Table& t, MaterialSpec& m, bool nonlocal) {
  const std::string form = fmt::format("{} (engineering constants) or {} (stiffness components)",
                                       kEngineeringList, kStiffnessList);
  const std::string needs =
      nonlocal ? fmt::format("an orthotropic material needs {}; the shear values may be left out", form)
               : fmt::format("an orthotropic material needs {}", form);
  double* const normal[6] = {&m.E1, &m.E2, &m.E3, &m.nu12, &m.nu13, &m.nu23};
  for (std::size_t k = 0; k < 6; ++k) {
    const Value v = t.require(kEngineeringKeys[k], needs);
    *normal[k] = k >= 3 ? v.number() : positive(v, "a Young's modulus");
  }
  double* const shears[3] = {&m.G23, &m.G13, &m.G12};  // in the order of shear_where
  for (std::size_t n = 0; n < 3; ++n) {                // read G12, G13, G23
    const std::size_t k = 2 - n;
    const std::string& key = kEngineeringKeys[6 + n];
    *shears[k] = read_shear(t, key, nonlocal, "shear modulus", form);
    m.shear_where[k] = location_of(t, key);
  }
  check_compliance(t, m);
}

void read_stiffness(const Table& t, MaterialSpec& m, bool nonlocal) {
  const std::string form = fmt::format("{} (stiffness components) or {} (engineering constants)",
                                       kStiffnessList, kEngineeringList);
  const std::string needs =
      nonlocal ? fmt::format("an orthotropic material needs {}; the shear values may be left out", form)
               : fmt::format("an orthotropic material needs {}", form);
  m.by_stiffness = true;
  Mat3 normal = Mat3::Zero();
  const int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
  for (std::size_t k = 0; k < 6; ++k) {
    const Value v = t.require(kStiffnessKeys[k], needs);
    normal(row[k], col[k]) = normal(col[k], row[k]) =
        k < 3 ? positive(v, "a normal stiffness component") : v.number();
  }
  // Normal block positive definite, by Sylvester's criterion: every 2 x 2
  // minor (a necessary condition that names the off-diagonal key), then det.
  for (std::size_t k = 3; k < 6; ++k) {
    const int i = row[k], j = col[k];
    if (!(normal(i, j) * normal(i, j) < normal(i, i) * normal(j, j)))
      t.get(kStiffnessKeys[k])
          ->fail(fmt::format(
              "{} = {} needs |{}| < sqrt({} {}) = {:.4g} for a positive-definite stiffness (a stable "
              "material)",
              kStiffnessKeys[k], normal(i, j), kStiffnessKeys[k], kStiffnessKeys[static_cast<std::size_t>(i)],
              kStiffnessKeys[static_cast<std::size_t>(j)], std::sqrt(normal(i, i) * normal(j, j))));
  }
  const double det = normal.determinant();
  if (!(det > 0))
    t.fail(fmt::format(
        "the normal stiffness components C1111 = {}, C2222 = {}, C3333 = {}, C1122 = {}, C1133 = {}, "
        "C2233 = {} are not positive definite (an unstable material): the determinant of [[C1111, C1122, "
        "C1133], [C1122, C2222, C2233], [C1133, C2233, C3333]] is {:.4g}, must be positive",
        normal(0, 0), normal(1, 1), normal(2, 2), normal(0, 1), normal(0, 2), normal(1, 2), det));
  m.stiffness.topLeftCorner<3, 3>() = normal;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string& key = kStiffnessKeys[6 + k];
    const int d = 3 + static_cast<int>(k);
    m.stiffness(d, d) = read_shear(t, key, nonlocal, "shear stiffness component", form);
    m.shear_where[k] = location_of(t, key);
  }
  // The engineering fields, for code that works with them.
  const Mat3 S = normal.inverse();
  m.E1 = 1 / S(0, 0);
  m.E2 = 1 / S(1, 1);
  m.E3 = 1 / S(2, 2);
  m.nu12 = -S(0, 1) * m.E1;
  m.nu13 = -S(0, 2) * m.E1;
  m.nu23 = -S(1, 2) * m.E2;
  m.G23 = m.stiffness(3, 3);
  m.G13 = m.stiffness(4, 4);
  m.G12 = m.stiffness(5, 5);
}

/// The first of `keys` that `t` has.
std::optional<Value> first_given(const Table& t, const std::vector<std::string>& keys) {
  for (const std::string& k : keys)
    if (auto v = t.get(k)) return v;
  return std::nullopt;
}

}  // namespace

/// Material axes from `rotation` (rows e1, e2, e3 in mesh coordinates):
/// checked to be a proper rotation within 1e-6, then made exactly orthonormal.
Mat3 read_rotation(const Value& v, int dim) {
  Mat3 r = v.matrix(3, "(rows = the material axes e1, e2, e3 in mesh coordinates)");
  const std::vector<Value> rows = v.elements();
  for (int i = 0; i < 3; ++i)
    if (std::abs(r.row(i).norm() - 1.0) > 1e-6)
      rows[static_cast<std::size_t>(i)].fail(
          fmt::format("row {} (material axis e{}) has length {:.7g}; every row must be a unit vector", i + 1,
                      i + 1, r.row(i).norm()));
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (std::abs(r.row(i).dot(r.row(j))) > 1e-6)
        v.fail(
            fmt::format("rows {} and {} (axes e{} and e{}) are not orthogonal: their dot product is {:.3g}",
                        i + 1, j + 1, i + 1, j + 1, r.row(i).dot(r.row(j))));
  if (r.determinant() < 0)
    v.fail("is a reflection (determinant -1); the axes must be right-handed (e3 = e1 x e2): reverse one row");
  if (dim == 2 && (r.col(2).cwiseAbs().maxCoeff() < 1.0 - 1e-6))
    v.fail(
        "in 2D one material axis must lie along z (a rotation about z, axes possibly permuted); otherwise "
        "the in-plane problem couples to out-of-plane shear");
  const Eigen::JacobiSVD<Mat3> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  r = svd.matrixU() * svd.matrixV().transpose();
  return r.transpose();  // columns = axes
}

void read_orthotropic(const Table& t, MaterialSpec& m, bool nonlocal) {
  const std::optional<Value> engineering = first_given(t, kEngineeringKeys);
  const std::optional<Value> stiffness = first_given(t, kStiffnessKeys);
  if (engineering && stiffness)
    stiffness->fail(fmt::format(
        "cannot be combined with {} (line {}): an orthotropic material is given either by engineering "
        "constants ({}) or by stiffness components ({}); pick one form",
        engineering->path(), engineering->where().line, kEngineeringList, kStiffnessList));
  if (stiffness)
    read_stiffness(t, m, nonlocal);
  else
    read_engineering(t, m, nonlocal);
}

// ------------------------------------------------------------ transversely isotropic

void read_transverse(const Table& t, MaterialSpec& m, bool nonlocal) {
  const std::string needs =
      nonlocal
          ? "a transversely-isotropic material (axis e3) needs E_in, E_axis, nu_axial (and optionally "
            "nu_in, G_axial)"
          : fmt::format(
                "a transversely-isotropic material (axis e3) needs E_in, E_axis, nu_axial, nu_in, G_axial "
                "(nu_in and G_axial may only be left out {})",
                kCentralForces);
  const double E_in = positive(t.require("E_in", needs), "the in-plane Young's modulus");
  const double E_axis = positive(t.require("E_axis", needs), "Young's modulus along the axis e3");
  const double nu_axial = t.require("nu_axial", needs).number();
  const std::optional<Value> nu_in_value = optional_in_nonlocal(t, "nu_in", nonlocal, needs);
  const double nu_in = nu_in_value ? nu_in_value->number() : kNaN;
  if (nu_in_value && !(nu_in > -1 && nu_in < 1))
    nu_in_value->fail(
        fmt::format("nu_in = {} is out of range: need -1 < nu_in < 1 (the in-plane Poisson ratio of a stable "
                    "material: the in-plane shear modulus E_in / (2 (1 + nu_in)) must be positive and the "
                    "in-plane compliance positive definite)",
                    nu_in));
  const std::optional<Value> G_value = optional_in_nonlocal(t, "G_axial", nonlocal, needs);
  const double G_axial = G_value ? positive(*G_value, "a shear modulus") : kNaN;

  m.E1 = m.E2 = E_in;
  m.E3 = E_axis;
  m.nu12 = nu_in;
  m.nu13 = m.nu23 = nu_axial;
  m.G12 = E_in / (2 * (1 + nu_in));
  m.G13 = m.G23 = G_axial;
  m.shear_where[0] = m.shear_where[1] = location_of(t, "G_axial");
  m.shear_where[2] = location_of(t, "nu_in");

  // The compliance conditions of check_compliance, for E1 = E2 and nu13 = nu23:
  // nu_in^2 < 1 (above), nu_axial^2 < E_in / E_axis and det S = (1 + nu_in)
  // (1 - nu_in - 2 nu_axial^2 E_axis / E_in) > 0. Without nu_in, the pair
  // condition alone keeps the central-force nu_in (docs) stable.
  if (!(nu_axial * nu_axial < E_in / E_axis))
    t.get("nu_axial")
        ->fail(fmt::format(
            "nu_axial = {} needs |nu_axial| < sqrt(E_in / E_axis) = {:.4g} for a positive-definite "
            "compliance (a stable material)",
            nu_axial, std::sqrt(E_in / E_axis)));
  if (nu_in_value) {
    const double factor = 1 - nu_in - 2 * nu_axial * nu_axial * E_axis / E_in;
    if (!(factor > 0))
      nu_in_value->fail(fmt::format(
          "nu_in = {} and nu_axial = {} make the compliance indefinite (an unstable material): 1 - "
          "nu_in - 2 nu_axial^2 E_axis / E_in = {:.4g} must be positive",
          nu_in, nu_axial, factor));
  }
}

}  // namespace perimorph::casefile::detail::material
