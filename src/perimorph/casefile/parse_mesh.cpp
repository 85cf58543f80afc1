// Case-file parsing of [mesh]: a structured box (type = "box", with holes
// and cuts) or a Gmsh file (type = "gmsh"). Format in docs/case-file.md;
// conventions as in parse_case.cpp.

#include "perimorph/casefile/parse_mesh.hpp"

#include "perimorph/casefile/choose_option.hpp"
#include "perimorph/casefile/toml_reader.hpp"
#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace perimorph::casefile::detail {

namespace {

constexpr int kMaxInt = std::numeric_limits<int>::max();

std::string for_dim(int dim) {
  return fmt::format("for dim = {}", dim);
}

double positive(const Value& v, std::string_view what) {
  const double x = v.number();
  if (!(x > 0)) v.fail(fmt::format("must be positive ({}), got {}", what, x));
  return x;
}

/// Refuses a box whose cells double precision cannot represent: a cell size
/// below the resolution of its node coordinates, a size whose inverse (the
/// shape-function gradients) or whose volume over- or underflows, or cells so
/// elongated that their stiffness is singular in double precision (its
/// eigenvalues span the aspect ratio squared: above 1/sqrt(machine epsilon)).
void check_cell_size(const Table& mesh, const BoxMesh& box) {
  const Value hi = mesh.require("upper", "the upper corner");
  const Value cells = mesh.require("cells", "the number of cells along each axis");
  const double eps = std::numeric_limits<double>::epsilon();
  double volume = 1.0, smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (int i = 0; i < box.dim; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double h = (box.upper[k] - box.lower[k]) / box.cells[k];
    const double scale = std::max(std::abs(box.lower[k]), std::abs(box.upper[k]));
    if (!(h > 1e3 * eps * scale) || !std::isnormal(h))
      hi.elements()[k].fail(fmt::format(
          "gives cells {:g} long along {} ({} cells between {} and {}): too small for double precision "
          "(below 1000 machine epsilons of the coordinates, or a subnormal number, whose inverse, the scale "
          "of the shape-function gradients, overflows); choose the box in units where the cells are not tiny "
          "against the coordinates (mm instead of m, or the box at the origin)",
          h, kAxis[i], box.cells[k], box.lower[k], box.upper[k]));
    volume *= h;
    smallest = std::min(smallest, h);
    largest = std::max(largest, h);
  }
  if (!std::isnormal(volume) || !std::isnormal(1.0 / volume))
    cells.fail(
        fmt::format("gives cells of {} {:g}, which double precision cannot hold (below {:g} or above "
                    "{:g}); choose other units for the box",
                    box.dim == 3   ? "volume"
                    : box.dim == 2 ? "area"
                                   : "length",
                    volume, std::numeric_limits<double>::min(), std::numeric_limits<double>::max()));
  if (largest / smallest > 1.0 / std::sqrt(eps))
    cells.fail(
        fmt::format("gives cells with aspect ratio {:.3g} (sizes {:g} to {:g}): above 1/sqrt(machine "
                    "epsilon) = {:.3g} their stiffness is singular in double precision; use more "
                    "cells along the long side or fewer along the short one",
                    largest / smallest, smallest, largest, 1.0 / std::sqrt(eps)));
}

CutSpec read_cut(const Table& t, const BoxMesh& box) {
  const int dim = box.dim;
  CutSpec cut;
  cut.where = t.where();
  const std::string shape1 = "a 1D cut is a point: at = x";
  const std::string shape2 = "a 2D cut is a segment: from = [x, y], to = [x, y]";
  const std::string shape3 = "a 3D cut is a parallelogram: origin = [x, y, z], edge1 = [...], edge2 = [...]";
  if (dim == 1) {
    t.check_keys(
        {"at"}, {{"from", shape1}, {"to", shape1}, {"origin", shape1}, {"edge1", shape1}, {"edge2", shape1}});
    const Value at = t.require("at", shape1);
    const double x = at.number();
    if (!(x > box.lower[0] && x < box.upper[0]))
      at.fail(fmt::format("the cut point must lie strictly inside the bar ({}, {}), got {}", box.lower[0],
                          box.upper[0], x));
    cut.origin = Vec3(x, 0, 0);
  } else if (dim == 2) {
    t.check_keys({"from", "to"}, {{"at", shape2}, {"origin", shape2}, {"edge1", shape2}, {"edge2", shape2}});
    const Vec3 from = t.require("from", shape2).vector(2, for_dim(2));
    const Value to_value = t.require("to", shape2);
    const Vec3 to = to_value.vector(2, for_dim(2));
    if ((to - from).norm() == 0.0)
      to_value.fail(fmt::format("the cut segment has zero length: to = from = {}", point(from, 2)));
    cut.origin = from;
    cut.edge1 = to - from;
  } else {
    t.check_keys({"origin", "edge1", "edge2"}, {{"at", shape3}, {"from", shape3}, {"to", shape3}});
    cut.origin = t.require("origin", shape3).vector(3, for_dim(3));
    cut.edge1 = t.require("edge1", shape3).vector(3, for_dim(3));
    const Value e2 = t.require("edge2", shape3);
    cut.edge2 = e2.vector(3, for_dim(3));
    const double scale = cut.edge1.norm() * cut.edge2.norm();
    if (!(cut.edge1.cross(cut.edge2).norm() > 1e-12 * scale))
      e2.fail(fmt::format(
          "edge1 = {} and edge2 = {} must be non-zero and not parallel (they span the cut's plane)",
          point(cut.edge1, 3), point(cut.edge2, 3)));
  }
  return cut;
}

const detail::Options<HoleShape> kHoleShapes{{"disk", HoleShape::disk},
                                             {"ball", HoleShape::ball},
                                             {"cylinder", HoleShape::cylinder},
                                             {"box", HoleShape::box}};

/// What a hole of `shape` takes, for messages.
std::string hole_takes(HoleShape shape, int dim) {
  constexpr const char* forms[3] = {"[x]", "[x, y]", "[x, y, z]"};
  const char* v = forms[dim - 1];
  switch (shape) {
    case HoleShape::disk:
      return fmt::format("a disk takes center = {} and radius", v);
    case HoleShape::ball:
      return fmt::format("a ball takes center = {} and radius", v);
    case HoleShape::cylinder:
      return fmt::format("a cylinder (axis along z) takes center = {} and radius", v);
    case HoleShape::box:
      return fmt::format("a box takes lower = {} and upper = {}", v, v);
  }
  return {};
}

HoleSpec read_hole(const Table& t, int dim) {
  // Every key of every shape first, so that a misspelt key gets a suggestion.
  const std::vector<std::string> every{"shape", "center", "radius", "lower", "upper"};
  t.check_keys(every);
  HoleSpec h;
  h.where = t.where();
  const Value shape =
      t.require("shape", "the hole's shape: \"disk\" (2D), \"ball\" (3D), \"cylinder\" (3D) or \"box\"");
  h.shape = detail::choose(shape, kHoleShapes, "hole shape");
  const std::string others = dim == 2   ? "\"disk\" or \"box\""
                             : dim == 3 ? "\"ball\", \"cylinder\" or \"box\""
                                        : "\"box\"";
  if (h.shape == HoleShape::disk && dim != 2)
    shape.fail(
        fmt::format("\"disk\" is a 2D shape, but mesh.dim = {}; {} use {}", dim, for_dim(dim), others));
  if ((h.shape == HoleShape::ball || h.shape == HoleShape::cylinder) && dim != 3)
    shape.fail(fmt::format("{:?} is a 3D shape, but mesh.dim = {}; {} use {}", shape.string(), dim,
                           for_dim(dim), others));
  const std::string takes = hole_takes(h.shape, dim);
  if (h.shape == HoleShape::box) {
    t.check_keys({"shape", "lower", "upper"}, {{"center", takes}, {"radius", takes}});
    read_box(t, dim, h.lower, h.upper);
  } else {
    t.check_keys({"shape", "center", "radius"}, {{"lower", takes}, {"upper", takes}});
    h.center = t.require("center", takes).vector(dim, for_dim(dim));
    h.radius = positive(t.require("radius", takes), "the hole's radius");
  }
  return h;
}

void read_box_mesh(const Table& mesh, CaseConfig& c) {
  BoxMesh& box = c.mesh.box;
  box.dim = mesh.require("dim", "the space dimension: 1, 2 or 3").integer(1, 3);
  const int dim = box.dim;
  read_box(mesh, dim, box.lower, box.upper);

  const Value cells =
      mesh.require("cells", fmt::format("the number of cells along each axis, {} integers", dim));
  if (!cells.node().is_array())
    cells.fail(fmt::format("expected an array of {} positive integers {}, got {}", dim, for_dim(dim),
                           detail::show(cells.node())));
  const std::vector<Value> counts = cells.elements();
  if (counts.size() != static_cast<std::size_t>(dim))
    cells.fail(fmt::format("needs {} positive integers {}, got {}: {}", dim, for_dim(dim), counts.size(),
                           detail::render(cells.node())));
  double nodes = 1.0;
  for (int i = 0; i < dim; ++i) {
    box.cells[static_cast<std::size_t>(i)] = counts[static_cast<std::size_t>(i)].integer(1, kMaxInt);
    nodes *= box.cells[static_cast<std::size_t>(i)] + 1.0;
  }
  if (nodes * dim > static_cast<double>(kMaxInt))
    cells.fail(
        fmt::format("gives {:.0f} nodes and {:.0f} displacement unknowns; at most {} are supported "
                    "(32-bit indices)",
                    nodes, nodes * dim, kMaxInt));

  check_cell_size(mesh, box);
}

/// [mesh] type = "gmsh": the file (relative to the case file's folder) and
/// the pre-crack groups. The file itself is read when the mesh is built
/// (setup/discretization.cpp), where a missing file or group is reported.
void read_gmsh_mesh(const Table& mesh, CaseConfig& c) {
  GmshMesh& g = c.mesh.gmsh;
  const Value file =
      mesh.require("file", "the Gmsh mesh file (.msh, format 4.1 or 2.2), e.g. file = \"part.msh\"");
  g.where = file.where();
  const std::filesystem::path given(file.name());
  const std::filesystem::path folder = std::filesystem::path(c.path).parent_path();
  g.file = (given.is_absolute() || folder.empty() ? given : folder / given).string();
  if (auto v = mesh.get("precrack")) {
    g.precrack_where = v->where();
    if (v->node().is_array()) {
      for (const Value& e : v->elements()) g.precracks.push_back(e.name());
      if (g.precracks.empty())
        v->fail("an empty list; give the names of physical groups, or leave the key out");
    } else {
      g.precracks.push_back(v->name());
    }
  }
}

}  // namespace

/// Reads `lower` and `upper` of a box (mesh or region) and checks that upper
/// exceeds lower along every axis.
void read_box(const Table& t, int dim, Vec3& lower, Vec3& upper) {
  const Value lo = t.require("lower", fmt::format("the lower corner, {} numbers", dim));
  const Value hi = t.require("upper", fmt::format("the upper corner, {} numbers", dim));
  lower = lo.vector(dim, for_dim(dim));
  upper = hi.vector(dim, for_dim(dim));
  for (int i = 0; i < dim; ++i)
    if (!(upper[i] > lower[i]))
      hi.elements()[static_cast<std::size_t>(i)].fail(
          fmt::format("must be greater than {}[{}] = {} (the box needs a positive extent along {}), got {}",
                      t.key_path("lower"), i + 1, lower[i], kAxis[i], upper[i]));
}

void read_mesh(const Table& root, CaseConfig& c) {
  const auto mesh = root.table("mesh");
  if (!mesh)
    root.fail(
        "missing required table [mesh] (keys type = \"box\", dim, lower, upper, cells); see "
        "docs/case-file.md");
  std::string type = "box";
  if (auto v = mesh->get("type")) {
    type = v->string();
    if (type != "box" && type != "gmsh")
      v->fail(fmt::format(
          "unknown mesh type {:?}; allowed: \"box\" (a structured grid of bars, quadrilaterals or "
          "hexahedra), \"gmsh\" (a Gmsh .msh file of quadrilaterals or hexahedra)",
          type));
  }
  if (type == "gmsh") {
    const std::string box_only = "lower, upper and cells belong to type = \"box\"; a Gmsh mesh has its own";
    mesh->check_keys({"type", "dim", "file", "precrack", "hole", "cut"},
                     {{"lower", box_only}, {"upper", box_only}, {"cells", box_only}});
    c.mesh.kind = MeshKind::gmsh;
    c.mesh.box.dim = mesh->require("dim", "the space dimension of the mesh: 2 or 3").integer(2, 3);
    read_gmsh_mesh(*mesh, c);
  } else {
    const std::string gmsh_only = "belongs to type = \"gmsh\" (a mesh file)";
    mesh->check_keys({"type", "dim", "lower", "upper", "cells", "hole", "cut"},
                     {{"file", gmsh_only}, {"precrack", gmsh_only}});
    read_box_mesh(*mesh, c);
  }
  for (const Table& t : mesh->tables("hole")) c.mesh.holes.push_back(read_hole(t, c.dim()));
  for (const Table& t : mesh->tables("cut")) c.mesh.cuts.push_back(read_cut(t, c.mesh.box));
}

}  // namespace perimorph::casefile::detail
