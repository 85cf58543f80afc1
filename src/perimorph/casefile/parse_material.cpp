// Case-file parsing of [[material]]: the material type and its keys,
// isotropic materials, the Cauchy rule of non-local cases and the list of
// materials. Orthotropic and transversely isotropic materials and material axes
// (`rotation`) are read in parse_material_anisotropic.cpp. Format in
// docs/case-file.md; conventions as in parse_case.cpp. Only the input is
// checked here (ranges, stability); whether central forces can represent a
// material is decided by the physics layer from the typed MaterialSpec.

#include "perimorph/casefile/parse_material.hpp"
#include "perimorph/casefile/parse_damage.hpp"

#include "perimorph/casefile/parse_material_detail.hpp"
#include "perimorph/casefile/suggest.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

namespace material {

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

}  // namespace material

namespace {

using namespace material;

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
  std::vector<std::string> allowed{"name", "region", "type", "cauchy", "damage"};
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
  read_material_damage(t, m);
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
