// Case-file parsing: one reader per section, in the order of docs/case-file.md.
// Each reader first rejects unknown keys (so a misspelt key is reported as
// such, not as a missing one), then reads and validates its keys. The first
// problem throws; the message says where, which key, the value and what is
// allowed.

#include "perimorph/casefile/parse_case.hpp"

#include "perimorph/casefile/choose_option.hpp"
#include "perimorph/casefile/parse_adaptivity.hpp"
#include "perimorph/casefile/parse_boundary.hpp"
#include "perimorph/casefile/parse_damage.hpp"
#include "perimorph/casefile/parse_fracture.hpp"
#include "perimorph/casefile/parse_material.hpp"
#include "perimorph/casefile/parse_mesh.hpp"
#include "perimorph/casefile/parse_nonlocal.hpp"
#include "perimorph/casefile/parse_run.hpp"
#include "perimorph/casefile/parse_sets.hpp"
#include "perimorph/casefile/toml_reader.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

namespace perimorph::casefile {

std::string SourceLocation::describe() const {
  if (key.empty()) return fmt::format("{}:{}:{}", file, line, column);
  return fmt::format("{}:{}:{}: key '{}'", file, line, column, key);
}

namespace {

using detail::Table;
using detail::Value;

using detail::kAxis;
using detail::point;

double positive(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x > 0)) v.fail(fmt::format("must be positive ({}), got {}", what, x));
  return x;
}

// ------------------------------------------------------------ [case]

void read_case(const Table& root, CaseConfig& c) {
  const auto t = root.table("case");
  if (!t) return;
  t->check_keys({"title"});
  if (auto v = t->get("title")) c.title = v->string();
}

// ------------------------------------------------------------ [[region]], [model]

void read_regions(const Table& root, CaseConfig& c) {
  const BoxMesh& box = c.mesh.box;
  for (const Table& t : root.tables("region")) {
    t.check_keys({"name", "lower", "upper", "set"});
    RegionSpec r;
    r.id = static_cast<int>(c.regions.size()) + 1;
    r.where = t.where();
    const Value name = t.require("name", "the region's name, which [[material]] region = \"...\" refers to");
    r.name = name.name();
    if (r.name == "all")
      name.fail(
          "the name \"all\" is reserved (it stands for every cell not in another material's region); "
          "choose another name");
    for (const RegionSpec& other : c.regions)
      if (other.name == r.name)
        name.fail(fmt::format(
            "duplicate region name {:?}: already used by {} (line {}); region names must be unique", r.name,
            other.where.key, other.where.line));
    if (auto set = t.get("set")) {
      if (t.has("lower") || t.has("upper"))
        set->fail("a region is either a box (lower, upper) or a mesh cell set (set), not both");
      r.set = set->name();
      c.regions.push_back(r);
      continue;
    }
    detail::read_box(t, box.dim, r.lower, r.upper);
    if (c.mesh.kind == MeshKind::box)
      for (int i = 0; i < box.dim; ++i)
        if (r.upper[i] <= box.lower[i] || r.lower[i] >= box.upper[i])
          t.fail(fmt::format(
              "the region box {} to {} lies outside the mesh box {} to {} (along {}), so it holds no cell",
              point(r.lower, box.dim), point(r.upper, box.dim), point(box.lower, box.dim),
              point(box.upper, box.dim), kAxis[i]));
    c.regions.push_back(r);
  }
}

void read_model(const Table& root, CaseConfig& c) {
  const auto t = root.table("model");
  if (!t) return;
  t->check_keys({"plane", "thickness", "local_quadrature"});
  const int dim = c.dim();
  if (auto v = t->get("plane")) {
    if (dim != 2)
      v->fail(fmt::format(
          "applies to 2D cases only (plane strain or plane stress), but mesh.dim = {}; remove it", dim));
    const std::string plane = v->string();
    if (plane == "strain")
      c.model.plane = PlaneMode::strain;
    else if (plane == "stress")
      c.model.plane = PlaneMode::stress;
    else
      v->fail(fmt::format("expected \"strain\" or \"stress\", got {:?}", plane));
  }
  if (auto v = t->get("thickness")) {
    if (dim == 3)
      v->fail(
          "applies to 1D (cross-section area) and 2D (out-of-plane thickness) cases only, but mesh.dim = 3; "
          "remove it");
    c.model.thickness = positive(*v, dim == 1 ? "the cross-section area" : "the out-of-plane thickness");
  }
  if (auto v = t->get("local_quadrature")) c.model.local_quadrature = v->integer(1, 10);
}

// ------------------------------------------------------------ boundary conditions

}  // namespace

CaseConfig parse_case_string(std::string_view toml_text, const std::string& pretend_path) {
  toml::table doc;
  try {
    doc = toml::parse(toml_text, std::string_view(pretend_path));
  } catch (const toml::parse_error& e) {
    SourceLocation at{pretend_path, 1, 1, ""};
    if (e.source().begin) {
      at.line = static_cast<int>(e.source().begin.line);
      at.column = static_cast<int>(e.source().begin.column);
    }
    detail::fail(at, fmt::format("TOML syntax error: {}", e.description()));
  }
  const Table root(pretend_path, doc, "");
  root.check_keys({"case", "mesh", "region", "node_set", "model", "material", "dirichlet", "traction",
                   "loading", "solver", "output", "nonlocal", "alpha", "fracture", "adaptivity", "damage"});
  CaseConfig c;
  c.path = pretend_path;
  c.text = std::string(toml_text);
  read_case(root, c);
  detail::read_mesh(root, c);
  read_regions(root, c);
  detail::read_node_sets(root, c);
  read_model(root, c);
  c.nonlocal.enabled = root.has("nonlocal");  // makes central-force values optional, allows `cauchy`
  detail::read_materials(root, c);
  detail::read_nonlocal(root, c);
  detail::read_alpha(root, c);
  detail::read_fracture(root, c);
  detail::read_damage(root, c);
  detail::read_adaptivity(root, c);
  detail::read_boundary(root, c);
  detail::read_loading(root, c);
  detail::read_solver(root, c);
  detail::read_output(root, c);
  return c;
}

CaseConfig parse_case_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("cannot open case file '{}': it is a directory", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw InputError(
        fmt::format("cannot open case file '{}' ({})", path, std::generic_category().message(err)));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("cannot read case file '{}'", path));
  return parse_case_string(text.str(), path);
}

}  // namespace perimorph::casefile
