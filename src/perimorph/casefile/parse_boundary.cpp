// Case-file parsing of the boundary conditions: [[dirichlet]] (prescribed
// displacements) and [[traction]]. Format in docs/case-file.md; conventions
// as in parse_case.cpp.

#include "perimorph/casefile/parse_boundary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Dense>

#include <string>
#include <utility>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};
constexpr const char* kDisplacement[3] = {"ux", "uy", "uz"};

std::string for_dim(int dim) {
  return fmt::format("for dim = {}", dim);
}

DirichletSpec read_dirichlet(const Table& t, int dim) {
  std::vector<std::string> allowed{"set", "gradient", "offset", "components"};
  std::vector<std::pair<std::string, std::string>> hints;
  const std::vector<std::string> comps(kDisplacement, kDisplacement + dim);
  for (int k = 0; k < 3; ++k) {
    if (k < dim)
      allowed.emplace_back(kDisplacement[k]);
    else
      hints.emplace_back(kDisplacement[k], fmt::format("the displacement has the components {} {}",
                                                       fmt::join(comps, ", "), for_dim(dim)));
  }
  t.check_keys(allowed, hints);
  DirichletSpec d;
  d.where = t.where();
  d.set = t.require("set", "the name of the node or face set to constrain, e.g. set = \"xmin\"").name();
  const std::optional<Value> gradient = t.get("gradient");
  std::vector<int> given;
  for (int k = 0; k < dim; ++k)
    if (t.has(kDisplacement[k])) given.push_back(k);
  if (!gradient) {
    for (const char* key : {"offset", "components"})
      if (auto v = t.get(key))
        v->fail(fmt::format("goes with gradient = [[...]]; without a gradient give constant components ({})",
                            fmt::join(comps, ", ")));
    if (given.empty())
      t.fail(fmt::format(
          "prescribes nothing: give constant components ({}) or gradient = [[...]] (with optional "
          "offset and components)",
          fmt::join(comps, ", ")));
    for (int k : given) {
      d.constrained[static_cast<std::size_t>(k)] = true;
      d.value[k] = t.get(kDisplacement[k])->number();
    }
    return d;
  }
  if (!given.empty())
    t.get(kDisplacement[given.front()])
        ->fail(
            "cannot be combined with gradient in one [[dirichlet]]; give either constants (ux, uy, uz) or "
            "gradient (with offset and components)");
  const std::string shape =
      fmt::format("(a {} x {} matrix {}, row c = the gradient of u_c)", dim, dim, for_dim(dim));
  d.gradient = gradient->matrix(dim, shape);
  if (auto v = t.get("offset")) d.value = v->vector(dim, for_dim(dim));
  if (auto v = t.get("components")) {
    const std::vector<Value> items = v->elements();
    const std::vector<std::string> axes(kAxis, kAxis + dim);
    if (items.empty()) v->fail(fmt::format("must list at least one of {:?}", fmt::join(axes, ", ")));
    for (const Value& item : items) {
      const std::string a = item.string();
      const auto it = std::find(axes.begin(), axes.end(), a);
      if (it == axes.end())
        item.fail(
            fmt::format("expected one of \"{}\" {}, got {:?}", fmt::join(axes, "\", \""), for_dim(dim), a));
      const auto k = static_cast<std::size_t>(it - axes.begin());
      if (d.constrained[k]) item.fail(fmt::format("component {:?} is listed twice", a));
      d.constrained[k] = true;
    }
  } else {
    for (int k = 0; k < dim; ++k) d.constrained[static_cast<std::size_t>(k)] = true;
  }
  for (int k = 0; k < 3; ++k)  // unconstrained components carry no data
    if (!d.constrained[static_cast<std::size_t>(k)]) {
      d.gradient.row(k).setZero();
      d.value[k] = 0.0;
    }
  return d;
}

}  // namespace

void read_boundary(const Table& root, CaseConfig& c) {
  const int dim = c.dim();
  for (const Table& t : root.tables("dirichlet")) c.dirichlet.push_back(read_dirichlet(t, dim));
  for (const Table& t : root.tables("traction")) {
    t.check_keys({"set", "value"});
    TractionSpec s;
    s.where = t.where();
    s.set = t.require("set", "the name of the face set loaded, e.g. set = \"ymax\"").name();
    s.value = t.require("value", fmt::format("the traction vector (force per area), {} numbers", dim))
                  .vector(dim, for_dim(dim));
    c.tractions.push_back(s);
  }
}

}  // namespace perimorph::casefile::detail
