#include "perimorph/mesh/gmsh_reader.hpp"

#include "perimorph/core/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gmsh.h>
#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <unordered_map>

namespace perimorph::mesh {

namespace {

constexpr int kGmshQuad4 = 3;
constexpr int kGmshHex8 = 5;
/// Gmsh's node order (counter-clockwise per face) to perimorph's lexicographic
/// one (mesh/cell_type.hpp): local node a of a perimorph cell is node
/// kFromGmsh[a] of the Gmsh element.
constexpr std::array<int, 8> kFromGmsh{0, 1, 3, 2, 4, 5, 7, 6};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(fmt::format("{}: {}", path, what));
}

/// Refuses what libgmsh would read silently or not at all: a missing file, a
/// .geo, a format version other than 4.1 and 2.2.
void check_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec))
    fail(path, "no such mesh file (a relative [mesh] file is taken from the case file's folder)");
  if (fs::path(path).extension() == ".geo")
    fail(path,
         fmt::format("a Gmsh geometry, not a mesh: mesh it first, e.g. `gmsh -2 {} -format msh41 -o {}` "
                     "(-3 for a 3D mesh), and give the .msh file",
                     path, fs::path(path).replace_extension(".msh").string()));
  std::ifstream in(path);
  if (!in) fail(path, "cannot be opened for reading");
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  if (line.rfind("$MeshFormat", 0) != 0)
    fail(path,
         "not a Gmsh mesh file in format 4.1 or 2.2 (it does not start with $MeshFormat; format 1 files "
         "are not read): write it with `gmsh ... -format msh41`");
  std::string version;
  if (std::getline(in, line)) std::istringstream(line) >> version;
  if (version != "4.1" && version != "2.2")
    fail(path, fmt::format("Gmsh mesh format version {:?}; perimorph reads 4.1 and 2.2: convert it with "
                           "`gmsh {} -0 -format msh41 -o new.msh`",
                           version, path));
}

/// One Gmsh session at a time (libgmsh holds global state), always finalized.
class GmshSession {
 public:
  GmshSession() : lock_(mutex()) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
};

std::string element_name(int type) {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary = 0;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
  return name;
}

/// "Quadrilateral 4", its count and the advice, for elements perimorph does not take.
[[noreturn]] void refuse_types(const std::string& path, int dim, const std::vector<int>& types,
                               const std::vector<std::vector<std::size_t>>& tags) {
  std::vector<std::string> found;
  for (std::size_t i = 0; i < types.size(); ++i)
    if (types[i] != (dim == 2 ? kGmshQuad4 : kGmshHex8))
      found.push_back(fmt::format("{} {} element(s) (Gmsh type {}, e.g. element {})", tags[i].size(),
                                  element_name(types[i]), types[i], tags[i].front()));
  fail(path,
       fmt::format("{}D cells must all be first-order {}; the file has {}. {}", dim,
                   dim == 2 ? "quadrilaterals" : "hexahedra", fmt::join(found, ", "),
                   dim == 2
                       ? "Recombine the triangles: `Recombine Surface{:};` or `Mesh.RecombineAll = 1;` "
                         "in the .geo (with `Mesh.SubdivisionAlgorithm = 1;` for quadrilaterals only), "
                         "and `Mesh.ElementOrder = 1;`"
                       : "Build hexahedra: extrude a recombined surface mesh (`Extrude {...} {Surface{..}; "
                         "Layers{n}; Recombine;}`), transfinite volumes with `Recombine Volume{:};`, or "
                         "`Mesh.SubdivisionAlgorithm = 2;` (every tetrahedron split into hexahedra); "
                         "and `Mesh.ElementOrder = 1;`"));
}

/// Smallest Jacobian determinant (up to the factor 2^-dim) at the corners of
/// a tensor-product cell with lexicographically numbered nodes x.
double smallest_corner_jacobian(const std::vector<Vec3>& x, int dim) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int a = 0; a < (1 << dim); ++a) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    for (int d = 0; d < dim; ++d) {
      const int lo = a & ~(1 << d), hi = a | (1 << d);
      J.col(d) = x[static_cast<std::size_t>(hi)] - x[static_cast<std::size_t>(lo)];
    }
    smallest = std::min(smallest, dim == 2 ? J.topLeftCorner<2, 2>().determinant() : J.determinant());
  }
  return smallest;
}

std::string group_name(int gdim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(gdim, tag, name);
  if (!name.empty()) return name;
  constexpr const char* kinds[4] = {"point", "curve", "surface", "volume"};
  return fmt::format("{}_{}", kinds[gdim], tag);
}

/// The sorted global nodes of a face, the key that matches a file's boundary
/// element with a cell's face.
std::vector<Index> sorted(std::vector<Index> v) {
  std::sort(v.begin(), v.end());
  return v;
}

Mesh read_open_model(const std::string& path, int dim) {
  // ---- cells of dimension dim, sorted by element tag
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, dim, -1);
  if (types.empty()) {
    std::vector<int> lower_types;
    std::vector<std::vector<std::size_t>> t, n;
    gmsh::model::mesh::getElements(lower_types, t, n, -1, -1);
    fail(path,
         fmt::format("has no element of dimension {} ({} element types of lower dimension): when a .geo "
                     "defines physical groups, Gmsh saves only their elements; add a `Physical {}` "
                     "holding the whole domain, or set `Mesh.SaveAll = 1;`",
                     dim, lower_types.size(), dim == 2 ? "Surface" : "Volume"));
  }
  if (types.size() != 1 || types[0] != (dim == 2 ? kGmshQuad4 : kGmshHex8))
    refuse_types(path, dim, types, element_tags);
  const int npc = 1 << dim;
  std::vector<std::size_t> order(element_tags[0].size());
  for (std::size_t e = 0; e < order.size(); ++e) order[e] = e;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return element_tags[0][a] < element_tags[0][b]; });

  // ---- nodes of the cells, by tag
  std::vector<std::size_t> node_tags;
  std::vector<double> coord, parametric;
  gmsh::model::mesh::getNodes(node_tags, coord, parametric, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> position;  // node tag -> index into node_tags
  for (std::size_t i = 0; i < node_tags.size(); ++i) position.emplace(node_tags[i], i);
  std::set<std::size_t> used(element_nodes[0].begin(), element_nodes[0].end());
  std::unordered_map<std::size_t, Index> node_index;  // node tag -> perimorph node
  std::vector<Vec3> nodes;
  const double extent = [&] {
    double e = 0.0;
    for (double c : coord) e = std::max(e, std::abs(c));
    return e;
  }();
  for (std::size_t tag : used) {
    const auto it = position.find(tag);
    if (it == position.end())
      fail(path, fmt::format("an element refers to node {}, which the file lacks", tag));
    const double* c = &coord[3 * it->second];
    if (dim == 2 && std::abs(c[2]) > 1e-12 * std::max(extent, 1.0))
      fail(path, fmt::format("a 2D mesh must lie in the plane z = 0; node {} is at z = {}", tag, c[2]));
    node_index.emplace(tag, static_cast<Index>(nodes.size()));
    nodes.emplace_back(c[0], c[1], dim == 2 ? 0.0 : c[2]);
  }

  std::vector<Index> cells;
  cells.reserve(order.size() * static_cast<std::size_t>(npc));
  std::unordered_map<std::size_t, Index> cell_index;  // element tag -> cell
  std::vector<Vec3> x(static_cast<std::size_t>(npc));
  for (std::size_t e : order) {
    for (int a = 0; a < npc; ++a) {
      const std::size_t tag =
          element_nodes[0][e * static_cast<std::size_t>(npc) +
                           static_cast<std::size_t>(kFromGmsh[static_cast<std::size_t>(a)])];
      cells.push_back(node_index.at(tag));
      x[static_cast<std::size_t>(a)] = nodes[static_cast<std::size_t>(cells.back())];
    }
    if (!(smallest_corner_jacobian(x, dim) > 0.0)) {
      Vec3 centroid = Vec3::Zero();
      for (const Vec3& p : x) centroid += p / npc;
      fail(path,
           fmt::format("element {} (centroid [{:.6g}, {:.6g}{}]) is inverted or degenerate: its Jacobian "
                       "is not positive at every corner{}",
                       element_tags[0][e], centroid.x(), centroid.y(),
                       dim == 3 ? fmt::format(", {:.6g}", centroid.z()) : std::string(),
                       dim == 2 ? " (a 2D element must run counter-clockwise seen from +z: reverse the "
                                  "surface, e.g. `ReverseMesh Surface{...};` in the .geo)"
                                : " (check the mesh with Gmsh's `Tools > Statistics`, or `gmsh -check`)"));
    }
    cell_index.emplace(element_tags[0][e], static_cast<Index>(cell_index.size()));
  }
  Mesh mesh(dim, std::move(nodes), std::move(cells));

  // ---- faces by their sorted nodes
  std::map<std::vector<Index>, std::vector<CellFace>> faces;
  for (Index c = 0; c < mesh.num_cells(); ++c)
    for (int f = 0; f < faces_per_cell(mesh.cell_type()); ++f) {
      std::vector<Index> key;
      for (int a : face_nodes(mesh.cell_type(), f)) key.push_back(mesh.cell(c)[static_cast<std::size_t>(a)]);
      faces[sorted(std::move(key))].push_back({c, f});
    }

  // ---- the implicit sets
  std::vector<Index> all(static_cast<std::size_t>(mesh.num_cells()));
  for (Index c = 0; c < mesh.num_cells(); ++c) all[static_cast<std::size_t>(c)] = c;
  mesh.cell_sets["all"] = std::move(all);
  std::vector<CellFace> boundary;
  for (const auto& [key, owners] : faces)
    if (owners.size() == 1) boundary.push_back(owners.front());
  std::sort(boundary.begin(), boundary.end());
  mesh.face_sets["boundary"] = boundary;
  mesh.node_sets["boundary"] = mesh.nodes_of_set("boundary");

  // ---- physical groups
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  std::map<std::string, std::string> described;  // name -> "physical curve 3"
  constexpr const char* kinds[4] = {"point", "curve", "surface", "volume"};
  for (const auto& [gdim, gtag] : groups) {
    if (gdim > dim) continue;
    const std::string name = group_name(gdim, gtag);
    const std::string what = fmt::format("physical {} {}", kinds[gdim], gtag);
    if (name == "all" || name == "boundary")
      fail(path, fmt::format("{} is named {:?}, the name of a set every mesh has; rename it", what, name));
    if (auto [it, fresh] = described.emplace(name, what); !fresh)
      fail(path,
           fmt::format("{} and {} are both named {:?}; set names must be unique", it->second, what, name));
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gdim, gtag, entities);
    if (gdim == dim) {
      std::vector<Index> set;
      for (int entity : entities) {
        std::vector<int> t;
        std::vector<std::vector<std::size_t>> tags, n;
        gmsh::model::mesh::getElements(t, tags, n, gdim, entity);
        for (const auto& block : tags)
          for (std::size_t tag : block) set.push_back(cell_index.at(tag));
      }
      std::sort(set.begin(), set.end());
      mesh.cell_sets[name] = std::move(set);
    } else if (gdim == dim - 1) {
      std::vector<CellFace> set;
      for (int entity : entities) {
        std::vector<int> t;
        std::vector<std::vector<std::size_t>> tags, n;
        gmsh::model::mesh::getElements(t, tags, n, gdim, entity);
        for (std::size_t b = 0; b < t.size(); ++b) {
          const std::size_t per = n[b].size() / std::max<std::size_t>(tags[b].size(), 1);
          for (std::size_t k = 0; k < tags[b].size(); ++k) {
            std::vector<Index> key;
            bool known = per == static_cast<std::size_t>(nodes_per_face(mesh.cell_type()));
            for (std::size_t j = 0; known && j < per; ++j) {
              const auto it = node_index.find(n[b][k * per + j]);
              if (it == node_index.end())
                known = false;
              else
                key.push_back(it->second);
            }
            const auto face = known ? faces.find(sorted(key)) : faces.end();
            if (face == faces.end())
              fail(path, fmt::format("{} ({:?}): its element {} ({}) is not the face of any {}D cell", what,
                                     name, tags[b][k], element_name(t[b]), dim));
            set.insert(set.end(), face->second.begin(), face->second.end());
          }
        }
      }
      std::sort(set.begin(), set.end());
      set.erase(std::unique(set.begin(), set.end()), set.end());
      mesh.face_sets[name] = std::move(set);
    } else {
      std::vector<std::size_t> tags;
      std::vector<double> c;
      gmsh::model::mesh::getNodesForPhysicalGroup(gdim, gtag, tags, c);
      std::vector<Index> set;
      for (std::size_t tag : tags)
        if (auto it = node_index.find(tag); it != node_index.end()) set.push_back(it->second);
      std::sort(set.begin(), set.end());
      mesh.node_sets[name] = std::move(set);
    }
  }
  return mesh;
}

}  // namespace

Mesh read_gmsh(const std::string& path, int dim) {
  PERIMORPH_ASSERT(dim == 2 || dim == 3, "Gmsh meshes are 2D or 3D");
  check_file(path);
  const GmshSession session;
  try {
    gmsh::open(path);
    std::string error;
    gmsh::logger::getLastError(error);
    if (!error.empty()) fail(path, fmt::format("Gmsh cannot read it: {}", error));
    return read_open_model(path, dim);
  } catch (const std::string& gmsh_error) {  // libgmsh throws its messages as std::string
    fail(path, fmt::format("Gmsh cannot read it: {}", gmsh_error));
  }
}

}  // namespace perimorph::mesh
