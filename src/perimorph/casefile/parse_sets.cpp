// Case-file parsing of [[node_set]]: named node sets selected by a box, for
// boundary conditions on single nodes or node rows. Format in
// docs/case-file.md; conventions as in parse_case.cpp. Which nodes a box
// selects is decided when the mesh is built (setup/discretization.cpp build_mesh).

#include "perimorph/casefile/parse_sets.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <string>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

std::string for_dim(int dim) {
  return fmt::format("for dim = {}", dim);
}

NodeSetSpec read_node_set(const Table& t, const CaseConfig& c, const std::vector<NodeSetSpec>& earlier) {
  t.check_keys({"name", "lower", "upper"});
  const int dim = c.dim();
  NodeSetSpec s;
  s.where = t.where();
  const Value name = t.require(
      "name", "the node set's name, which [[dirichlet]] set = \"...\" refers to, e.g. name = \"pin\"");
  s.name = name.name();
  const std::vector<std::string> reserved =
      c.mesh.kind == MeshKind::box ? mesh_set_names() : std::vector<std::string>{"boundary", "all"};
  if (std::find(reserved.begin(), reserved.end(), s.name) != reserved.end())
    name.fail(
        fmt::format("the name {:?} is already a set of the mesh (every {} mesh has {}); choose another name",
                    s.name, c.mesh.kind == MeshKind::box ? "box" : "Gmsh", fmt::join(reserved, ", ")));
  for (const RegionSpec& r : c.regions)
    if (r.name == s.name)
      name.fail(
          fmt::format("the name {:?} is already used by a region ({}, line {}); node set names must differ "
                      "from region names",
                      s.name, r.where.key, r.where.line));
  for (const NodeSetSpec& other : earlier)
    if (other.name == s.name)
      name.fail(
          fmt::format("duplicate node set name {:?}: already used by {} (line {}); node set names must be "
                      "unique",
                      s.name, other.where.key, other.where.line));

  s.lower =
      t.require("lower", fmt::format("the lower corner of the box that selects the nodes, {} numbers", dim))
          .vector(dim, for_dim(dim));
  const Value hi =
      t.require("upper", fmt::format("the upper corner of the box that selects the nodes, {} numbers", dim));
  s.upper = hi.vector(dim, for_dim(dim));
  for (int i = 0; i < dim; ++i)
    if (!(s.upper[i] >= s.lower[i]))
      hi.elements()[static_cast<std::size_t>(i)].fail(fmt::format(
          "must not be less than {}[{}] = {} (equal bounds select a plane, line or point along {}), "
          "got {}",
          t.key_path("lower"), i + 1, s.lower[i], kAxis[i], s.upper[i]));
  return s;
}

}  // namespace

const std::vector<std::string>& mesh_set_names() {
  static const std::vector<std::string> names{"xmin", "xmax", "ymin",     "ymax",
                                              "zmin", "zmax", "boundary", "all"};
  return names;
}

void read_node_sets(const Table& root, CaseConfig& c) {
  for (const Table& t : root.tables("node_set")) {
    NodeSetSpec s = read_node_set(t, c, c.node_sets);
    c.node_sets.push_back(std::move(s));
  }
}

}  // namespace perimorph::casefile::detail
