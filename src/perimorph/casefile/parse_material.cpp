// Case-file parsing of [[material]]: isotropic, orthotropic (engineering
// constants or stiffness components) and transversely isotropic materials,
// material axes (`rotation`) and the Cauchy rule of non-local cases. Format in
// docs/case-file.md; conventions as in parse_case.cpp. Only the input is
// checked here (ranges, stability); whether central forces can represent a
// material is decided by the physics layer from the typed MaterialSpec.

#include "perimorph/casefile/parse_material.hpp"

#include "perimorph/casefile/suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<std::string> kIsotropicKeys{"E", "nu"};
/// Engineering constants; the last three are the shear moduli.
const std::vector<std::string> kEngineeringKeys{"E1",   "E2",  "E3",  "nu12", "nu13",
                                                "nu23", "G12", "G13", "G23"};
/// Stiffness components: C1111, C2222, C3333, C1122, C1133, C2233, then the
/// shear ones in the order of MaterialSpec::shear_where (C2323, C1313, C1212).
const std::vector<std::string> kStiffnessKeys{"C1111", "C2222", "C3333", "C1122", "C1133",
                                              "C2233", "C2323", "C1313", "C1212"};
const std::vector<std::string> kTransverseKeys{"E_in", "E_axis", "nu_axial", "nu_in", "G_axial"};

constexpr const char* kEngineeringList = "E1, E2, E3, nu12, nu13, nu23, G12, G13, G23";
constexpr const char* kStiffnessList = "C1111, C2222, C3333, C1122, C1133, C2233, C2323, C1313, C1212";
constexpr const char* kCentralForces = "with [nonlocal], where central forces determine them";

double positive(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x > 0)) v.fail(fmt::format("must be positive ({}), got {}", what, x));
  return x;
}

/// The location of `key` in `t`: where it is given, else t's header labelled
/// with the key's path.
SourceLocation location_of(const Table& t, std::string_view key) {
  if (auto v = t.get(key)) return v->where();
  SourceLocation at = t.where();
  at.key = t.key_path(key);
  return at;
}

/// A value that [nonlocal] makes optional (one that central forces determine):
/// required without [nonlocal] (failing with `needs`), NaN when left out.
std::optional<Value> optional_in_nonlocal(const Table& t, const std::string& key, bool nonlocal,
                                          std::string_view needs) {
  if (nonlocal) return t.get(key);
  return t.require(key, needs);
}

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

std::string type_name(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::isotropic:
      return "isotropic";
    case MaterialKind::orthotropic:
      return "orthotropic";
    case MaterialKind::transversely_isotropic:
      break;
  }
  return "transversely-isotropic";
}

/// The keys of a material type (besides name, region, type, cauchy, rotation).
std::vector<std::string> keys_of(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::isotropic:
      return kIsotropicKeys;
    case MaterialKind::orthotropic: {
      std::vector<std::string> keys = kEngineeringKeys;
      keys.insert(keys.end(), kStiffnessKeys.begin(), kStiffnessKeys.end());
      return keys;
    }
    case MaterialKind::transversely_isotropic:
      break;
  }
  return kTransverseKeys;
}

/// "an orthotropic material takes ...", for a key of another type.
std::string takes(MaterialKind kind) {
  switch (kind) {
    case MaterialKind::isotropic:
      return "an isotropic material takes E and nu";
    case MaterialKind::orthotropic:
      return fmt::format(
          "an orthotropic material takes {} (engineering constants) or {} (stiffness components)",
          kEngineeringList, kStiffnessList);
    case MaterialKind::transversely_isotropic:
      break;
  }
  return "a transversely-isotropic material takes E_in, E_axis, nu_axial, nu_in, G_axial (axis e3)";
}

MaterialKind read_type(const Table& t) {
  const std::optional<Value> v = t.get("type");
  if (!v) return MaterialKind::isotropic;
  const std::string type = v->string();
  const MaterialKind kinds[3] = {MaterialKind::isotropic, MaterialKind::orthotropic,
                                 MaterialKind::transversely_isotropic};
  std::vector<std::string> names;
  for (MaterialKind kind : kinds) {
    if (type == type_name(kind)) return kind;
    names.push_back(type_name(kind));
  }
  const std::string close = closest_match(type, names);
  v->fail(fmt::format(
      "unknown material type {:?}; {}allowed: \"isotropic\" (E, nu), \"orthotropic\" ({} or {}; "
      "rotation) or \"transversely-isotropic\" (E_in, E_axis, nu_axial, nu_in, G_axial; rotation)",
      type, close.empty() ? "" : fmt::format("did you mean {:?}? ", close), kEngineeringList,
      kStiffnessList));
}

void check_material_keys(const Table& t, MaterialKind kind) {
  std::vector<std::string> allowed{"name", "region", "type", "cauchy"};
  std::vector<std::pair<std::string, std::string>> hints;
  const std::string self = type_name(kind);
  for (MaterialKind other :
       {MaterialKind::isotropic, MaterialKind::orthotropic, MaterialKind::transversely_isotropic}) {
    for (const std::string& k : keys_of(other)) {
      if (other == kind)
        allowed.push_back(k);
      else if (other == MaterialKind::isotropic)
        hints.emplace_back(k, takes(kind));
      else
        hints.emplace_back(k, fmt::format("it belongs to {} materials; set type = {:?} (this one is {})",
                                          type_name(other), type_name(other), self));
    }
  }
  if (kind != MaterialKind::isotropic)
    allowed.emplace_back("rotation");
  else
    hints.emplace_back("rotation",
                       "only orthotropic and transversely-isotropic materials have axes; set type = "
                       "\"orthotropic\" or \"transversely-isotropic\"");
  t.check_keys(allowed, hints);
}

// ------------------------------------------------------------ isotropic

/// `nu` is optional in non-local cases: NaN when absent (the physics layer
/// then takes the central-force value and checks a given one).
void read_isotropic(const Table& t, MaterialSpec& m, bool nonlocal) {
  const std::string needs =
      nonlocal ? "an isotropic material needs Young's modulus E (and optionally Poisson's ratio nu)"
               : "an isotropic material needs Young's modulus E and Poisson's ratio nu (nu may be left out "
                 "only in non-local cases, with [nonlocal])";
  m.E = positive(t.require("E", needs), "Young's modulus");
  m.nu_where = location_of(t, "nu");
  const std::optional<Value> given = optional_in_nonlocal(t, "nu", nonlocal, needs);
  if (!given) {
    m.nu = kNaN;
    return;
  }
  const Value& nu = *given;
  m.nu = nu.number();
  if (m.nu >= 0.5)
    nu.fail(
        fmt::format("nu = {} is out of range: need -1 < nu < 0.5; a Poisson ratio of 0.5 or more makes an "
                    "isotropic material incompressible (0.5) or unstable (above 0.5)",
                    m.nu));
  if (m.nu <= -1.0)
    nu.fail(
        fmt::format("nu = {} is out of range: need -1 < nu < 0.5; a Poisson ratio of -1 or less makes the "
                    "shear modulus E / (2 (1 + nu)) zero or negative, an unstable material",
                    m.nu));
}

// ------------------------------------------------------------ orthotropic

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

// ------------------------------------------------------------ common

void read_cauchy(const Table& t, MaterialSpec& m, bool nonlocal) {
  m.cauchy_where = location_of(t, "cauchy");
  const std::optional<Value> v = t.get("cauchy");
  if (!v) return;
  if (!nonlocal)
    v->fail(
        "only matters for the non-local model (how a material that central forces cannot represent is "
        "treated), but this case has no [nonlocal] section; remove it");
  const std::string rule = v->string();
  if (rule == "exact") {
    m.cauchy = CauchyRule::exact;
  } else if (rule == "nearest") {
    m.cauchy = CauchyRule::nearest;
  } else {
    const std::string close = closest_match(rule, {"exact", "nearest"});
    v->fail(fmt::format(
        "unknown cauchy rule {:?}; {}allowed: \"exact\" (a given value inconsistent with the Cauchy "
        "relations is an error) or \"nearest\" (the stiffness is replaced by its nearest central-force "
        "stiffness)",
        rule, close.empty() ? "" : fmt::format("did you mean {:?}? ", close)));
  }
}

MaterialSpec read_material(const Table& t, const CaseConfig& c) {
  MaterialSpec m;
  m.where = t.where();
  m.kind = read_type(t);
  check_material_keys(t, m.kind);

  m.name = t.require("name", "every material needs a name, e.g. name = \"steel\"").name();
  if (auto v = t.get("region")) {
    m.region = v->name();
    std::vector<std::string> known{"all"};
    for (const RegionSpec& r : c.regions) known.push_back(r.name);
    if (std::find(known.begin(), known.end(), m.region) == known.end()) {
      const std::string close = closest_match(m.region, known);
      v->fail(fmt::format("region {:?} is not declared{}; known regions: {}", m.region,
                          close.empty() ? "" : fmt::format(" (did you mean {:?}?)", close),
                          fmt::join(known, ", ")));
    }
  }
  const bool nonlocal = c.nonlocal.enabled;
  switch (m.kind) {
    case MaterialKind::isotropic:
      read_isotropic(t, m, nonlocal);
      break;
    case MaterialKind::orthotropic:
      read_orthotropic(t, m, nonlocal);
      break;
    case MaterialKind::transversely_isotropic:
      read_transverse(t, m, nonlocal);
      break;
  }
  if (m.kind != MaterialKind::isotropic)
    if (auto v = t.get("rotation")) m.axes = read_rotation(*v, c.dim());
  read_cauchy(t, m, nonlocal);
  return m;
}

}  // namespace

void read_materials(const Table& root, CaseConfig& c) {
  const std::vector<Table> tables = root.tables("material");
  if (tables.empty())
    root.fail(
        "no [[material]] given; at least one is required, e.g. [[material]] with name = \"steel\", "
        "E = 210000, nu = 0.3");
  for (const Table& t : tables) {
    MaterialSpec m = read_material(t, c);
    for (const MaterialSpec& other : c.materials) {
      if (other.name == m.name)
        t.get("name")->fail(fmt::format("duplicate material name {:?}: already used by {} (line {})", m.name,
                                        other.where.key, other.where.line));
      if (other.region == m.region)
        t.fail(
            fmt::format("region {:?} already has material {:?} ({}, line {}); each region takes one material",
                        m.region, other.name, other.where.key, other.where.line));
    }
    c.materials.push_back(std::move(m));
  }
}

}  // namespace perimorph::casefile::detail
