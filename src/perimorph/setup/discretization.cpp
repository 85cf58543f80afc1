#include "perimorph/setup/discretization.hpp"

#include "perimorph/assembly/discrete_calibration.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/cut.hpp"
#include "perimorph/mesh/gmsh_reader.hpp"
#include "perimorph/mesh/holes.hpp"
#include "perimorph/partition/partition.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace perimorph::setup {

namespace {

bool inside(const Vec3& x, const Vec3& lo, const Vec3& hi, int dim) {
  for (int d = 0; d < dim; ++d)
    if (x[d] < lo[d] || x[d] > hi[d]) return false;
  return true;
}

/// "[0, 24]": the first n components of v.
std::string point(const Vec3& v, int n) {
  return fmt::format("[{}]", fmt::join(v.data(), v.data() + n, ", "));
}

/// Fills m.node_sets[s.name] with the nodes in the box of s, widened by tol;
/// an error if it selects none on the whole mesh (`whole`: m may be a window).
void add_node_set(mesh::Mesh& m, const casefile::NodeSetSpec& s, double tol, const WholeMeshChecks& whole) {
  const int dim = m.dim();
  const auto names = m.set_names();
  if (std::find(names.begin(), names.end(), s.name) != names.end())
    throw InputError(
        fmt::format("{}: node set '{}': the mesh already has a set of that name; choose another name",
                    s.where.describe(), s.name));
  const Vec3 lo = s.lower - Vec3::Constant(tol), hi = s.upper + Vec3::Constant(tol);
  std::vector<Index> nodes;
  for (Index n = 0; n < m.num_nodes(); ++n)
    if (inside(m.node(n), lo, hi, dim)) nodes.push_back(n);
  if (!whole.any(!nodes.empty()))
    throw InputError(
        fmt::format("{}: node set '{}' (box {} to {}) selects no mesh node; enlarge its box to reach "
                    "a node (the mesh spans {} to {})",
                    s.where.describe(), s.name, point(s.lower, dim), point(s.upper, dim),
                    point(whole.bounds_of(m).first, dim), point(whole.bounds_of(m).second, dim)));
  m.node_sets[s.name] = std::move(nodes);
}

std::string face_set_names(const mesh::Mesh& m) {
  std::vector<std::string> names;
  for (const auto& [name, set] : m.face_sets) names.push_back(name);
  return fmt::format("{}", fmt::join(names, ", "));
}

std::string cell_set_names(const mesh::Mesh& m) {
  std::vector<std::string> names;
  for (const auto& [name, set] : m.cell_sets) names.push_back(name);
  return fmt::format("{}", fmt::join(names, ", "));
}

/// The mesh of [mesh]: a box, or the Gmsh file with its pre-crack groups split.
mesh::Mesh make_mesh(const casefile::CaseConfig& config) {
  const auto& box = config.mesh.box;
  if (config.mesh.kind == casefile::MeshKind::box) return mesh::make_box(box_of(config));
  const auto& g = config.mesh.gmsh;
  mesh::Mesh m = [&] {
    try {
      return mesh::read_gmsh(g.file, box.dim);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", g.where.describe(), e.what()));
    }
  }();
  for (const std::string& name : g.precracks) {
    const auto it = m.face_sets.find(name);
    if (it == m.face_sets.end())
      throw InputError(fmt::format(
          "{}: the pre-crack {:?} is not a face group of {} (a physical {} of the mesh); its face groups: {}",
          g.precrack_where.describe(), name, g.file, box.dim == 2 ? "curve" : "surface", face_set_names(m)));
    mesh::split_along_faces(m, it->second);
  }
  return m;
}

}  // namespace

mesh::Mesh shape_mesh(const casefile::CaseConfig& config, mesh::Mesh m, const WholeMeshChecks& whole) {
  const auto& box = config.mesh.box;
  for (const auto& h : config.mesh.holes) {  // before regions and cuts: they see the holed mesh
    try {
      mesh::remove_hole(m, Hole{box.dim, h.shape, h.center, h.radius, h.lower, h.upper});
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", h.where.describe(), e.what()));
    }
  }
  for (const auto& r : config.regions) {
    std::vector<Index> cells;
    if (!r.set.empty()) {
      const auto it = m.cell_sets.find(r.set);
      if (it == m.cell_sets.end())
        throw InputError(fmt::format("{}: region '{}': the mesh has no cell set {:?}; its cell sets: {}",
                                     r.where.describe(), r.name, r.set, cell_set_names(m)));
      cells = it->second;
    } else {
      for (Index c = 0; c < m.num_cells(); ++c)
        if (inside(m.cell_centroid(c), r.lower, r.upper, box.dim)) cells.push_back(c);
    }
    for (Index c : cells) m.cell_region[static_cast<std::size_t>(c)] = r.id;
    if (!whole.any(!cells.empty()))
      throw InputError(
          fmt::format("{}: region '{}' contains no cell centroid; enlarge its box or refine the mesh",
                      r.where.describe(), r.name));
    m.cell_sets[r.name] = std::move(cells);
  }
  for (const auto& c : config.mesh.cuts) {
    try {
      mesh::split_along_cut(m, Cut{box.dim, c.origin, c.edge1, c.edge2});
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", c.where.describe(), e.what()));
    }
  }
  // After the cuts, so that both copies of a split node are selected.
  if (!config.node_sets.empty()) {
    const auto [lo, hi] = whole.bounds_of(m);
    double extent = 0.0;
    for (int d = 0; d < box.dim; ++d) extent = std::max(extent, hi[d] - lo[d]);
    const double tol = 1e-9 * extent;
    for (const auto& s : config.node_sets) add_node_set(m, s, tol, whole);
  }
  return m;
}

mesh::Mesh build_mesh(const casefile::CaseConfig& config) {
  return shape_mesh(config, make_mesh(config), {});
}

Voigt6 material_stiffness(const casefile::MaterialSpec& m) {
  std::string problem;
  Voigt6 C;
  if (m.kind == casefile::MaterialKind::isotropic) {
    const fem::IsotropicElasticity iso{m.E, m.nu};
    problem = fem::admissibility_problem(iso);
    C = fem::stiffness_voigt(iso);
  } else {
    const fem::OrthotropicElasticity ortho{m.E1,   m.E2,  m.E3,  m.nu12, m.nu13,
                                           m.nu23, m.G12, m.G13, m.G23,  m.axes};
    problem = fem::admissibility_problem(ortho);
    C = fem::stiffness_voigt(ortho);
  }
  if (!problem.empty())
    throw InputError(fmt::format("{}: material '{}': {}", m.where.describe(), m.name, problem));
  return C;
}

namespace {

/// What α decides (THEORY §3–§4), for a discretization whose mesh, local
/// quadrature, material and calibrated kernel are set: the non-local points
/// (α at each), the cell graph (pairs with α > 0 within reach), the morphed C
/// at the local points, the CG/DG flags and the dof map. With `config_check`,
/// an [[alpha.region]] that reaches no point is an InputError (a case error;
/// not checked on a rebuild).
void place_alpha(Discretization& d, alpha::AlphaField alpha, const std::function<void(const char*)>& phase,
                 bool config_check, const WholeMeshChecks& whole = {},
                 const std::function<double(double)>& max_over_processes = {}) {
  const auto& config = d.config;
  const mesh::Mesh& m = d.mesh;
  const int dim = m.dim();
  auto& nl = *d.nonlocal;
  const bool partial_volume = config.nonlocal.horizon_edge == casefile::HorizonEdge::partial_volume;
  phase("points");
  nl.alpha = std::move(alpha);
  // A part stores the points of the cells it reads, known with its graph
  // rows (below); until then, none (the per-cell α bounds are whole).
  const bool part = !d.computed_cells.empty();
  nl.points =
      part ? bonds::make_nonlocal_points(m, config.nonlocal.quadrature, d.scale, nl.alpha, partial_volume,
                                         std::vector<char>(static_cast<std::size_t>(m.num_cells()), 0))
           : bonds::make_nonlocal_points(m, config.nonlocal.quadrature, d.scale, nl.alpha, partial_volume);
  // On a window the points' bound is the whole mesh's: the maximum over the
  // windows (which cover it), or on a rebuild the one found then.
  if (d.window)
    nl.points.half_bound =
        max_over_processes ? max_over_processes(nl.points.half_bound) : d.window->half_bound;
  if (config_check) check_alpha_regions(config, nl.alpha, nl.points, m, d.rule, whole);
  phase("bond graph");
  const auto& amax = nl.points.cell_alpha_max;
  // Boxes of the local and non-local points: the graph must hold every cell
  // the bonds of a non-local point or the horizon integral of a local point
  // (the morphed C) can reach.
  std::vector<Vec3> reference;
  for (const auto& q : fem::gauss_legendre(dim, config.nonlocal.quadrature)) reference.push_back(q.xi);
  for (const auto& q : d.rule) reference.push_back(q.xi);
  nl.cuts = bonds::CutNeighborhood(m, nl.points.bond_reach(nl.kernel.horizon));
  // Matrix-free (α ≡ 1, check_matrix_free): no pair is ever assembled, the
  // operator's blocks come from a small model (system/matrix_free_stiffness.hpp);
  // every cell purely non-local needs no neighbour for the morphed C (= 0).
  if (config.solver.op == casefile::SolverOperator::matrix_free)
    nl.graph = bonds::CellGraph::diagonal(m.num_cells());
  else
    nl.graph = bonds::find_cell_neighbors(
        m, bonds::point_boxes(m, reference), nl.points.bond_reach(nl.kernel.horizon),
        [&](Index e, Index f) {
          return amax[static_cast<std::size_t>(e)] > 0.0 || amax[static_cast<std::size_t>(f)] > 0.0;
        },
        d.computed_cells);
  if (part) bonds::store_points(nl.points, m, nl.alpha, nl.graph.cells_in_rows(d.computed_cells));
  phase("morphed stiffness");
  d.stiffness = fem::ConstitutiveField(dim, m.num_cells(), static_cast<int>(d.rule.size()));
  nl.morph = assembly::morph_stiffness(m, d.rule, nl.points, nl.graph, nl.kernel, nl.alpha, nl.material.C0,
                                       config.nonlocal.coupling == casefile::Coupling::partition
                                           ? assembly::CouplingRule::partition
                                           : assembly::CouplingRule::morphing,
                                       d.stiffness, d.computed_cells, d.share_flags);
  if (d.damage && !d.damage->laws.empty()) {
    // THEORY §6: the morphing acts on the residual branch (1 − d_c) C₀ only;
    // the damageable branch d_c C₀ (lowered by d during a run) is local everywhere.
    const std::size_t law = 0;  // [nonlocal] has one material (nonlocal_material)
    d.stiffness.add_to_all(d.damage->laws[law].d_c * d.damage->C0[law]);
  }
  std::vector<dofs::Continuity> continuity;
  const auto dg = config.nonlocal.discretization;
  if (dg != casefile::Discretization::continuous) {
    const auto flag = dg == casefile::Discretization::discontinuous
                          ? dofs::Continuity::discontinuous
                          : dofs::Continuity::discontinuous_constant;
    continuity.assign(static_cast<std::size_t>(m.num_cells()), dofs::Continuity::continuous);
    for (Index c = 0; c < m.num_cells(); ++c)
      if (nl.morph.purely_nonlocal[static_cast<std::size_t>(c)])
        continuity[static_cast<std::size_t>(c)] = flag;
  }
  phase("dof map");
  d.dofmap = dofs::DofMap(m, dim, continuity);
}

}  // namespace

void check_matrix_free(const casefile::CaseConfig& config) {
  if (config.solver.op != casefile::SolverOperator::matrix_free) return;
  std::string why;
  if (config.mesh.kind != casefile::MeshKind::box)
    why = "the mesh is not a box (a Gmsh mesh has no grid)";
  else if (!config.mesh.holes.empty())
    why = fmt::format("the mesh has a hole (line {})", config.mesh.holes.front().where.line);
  else if (!config.mesh.cuts.empty())
    why = fmt::format("the mesh has a pre-crack cut (line {}): the bonds across it are missing",
                      config.mesh.cuts.front().where.line);
  else if (!config.nonlocal.enabled)
    why = "there is no [nonlocal] section";
  else if (config.materials.size() != 1)
    why = fmt::format("the case has {} materials (the grid must be one material)", config.materials.size());
  else if (config.nonlocal.quadrature != 1)
    why = fmt::format("[nonlocal] quadrature is {}, not 1 (one non-local point per cell)",
                      config.nonlocal.quadrature);
  else if (config.nonlocal.discretization != casefile::Discretization::discontinuous_constant)
    why = "[nonlocal] discretization is not \"discontinuous-constant\" (one node per cell)";
  else if (config.alpha.value != 1.0 || !config.alpha.regions.empty())
    why =
        config.alpha.regions.empty()
            ? fmt::format("[alpha] value is {}, not 1 (the operator is purely non-local)", config.alpha.value)
            : fmt::format("[[alpha.region]] at line {} makes alpha vary",
                          config.alpha.regions.front().where.line);
  else if (config.fracture.enabled)
    why = "the case has [fracture]: failed bonds change the operator";
  else if (config.has_damage())
    why = "a material has [material.damage]";
  else if (config.adaptivity.enabled)
    why = "the case has [adaptivity]";
  if (!why.empty())
    throw InputError(fmt::format(
        "{}: operator = \"matrix-free\" covers the elastic non-local operator of a box grid with alpha = 1 "
        "everywhere and [nonlocal] discretization = \"discontinuous-constant\" (no hole, cut, fracture, "
        "damage or adaptivity), where every bond depends only on its grid offset; {}. Use operator = "
        "\"assembled\" (the default)",
        config.solver.operator_where.describe(), why));
}

Discretization build_discretization(const casefile::CaseConfig& config, const PhaseCallback& on_phase,
                                    ModelPart part) {
  auto phase = [&](const char* name) {
    if (on_phase) on_phase(name);
  };
  check_matrix_free(config);
  phase("mesh");
  std::shared_ptr<WindowNumbers> window;
  mesh::Mesh m = part.window ? window_mesh(config, *part.window, window) : build_mesh(config);
  const int dim = m.dim();
  const double scale = dim == 3 ? 1.0 : config.model.thickness;
  auto rule = fem::gauss_legendre(dim, config.model.local_quadrature);
  fem::ConstitutiveField field(dim, m.num_cells(), static_cast<int>(rule.size()));

  std::optional<NonlocalModel> nl;
  Eigen::MatrixXd full_C0;  // [nonlocal]: the resolved material's C₀, before the residual scaling
  phase("material");
  if (config.nonlocal.enabled) {
    nl.emplace();
    nl->material = nonlocal_material(config);
    full_C0 = nl->material.C0;
    if (const auto& damage = nl->material.spec.damage; damage.enabled) {
      // THEORY §6 (3.45): the micromodulus is calibrated to the residual branch (1 − d_c) C₀.
      const double residual = 1.0 - damage.d_c;
      nl->material.E *= residual;
      nl->material.C0 *= residual;
      nl->material.notes.push_back(fmt::format(
          "calibrated to the residual branch (1 - d_c) C0 of the damage law, d_c = {:g}", damage.d_c));
    }
    nl->kernel = make_kernel(config.nonlocal);
    nl->calibration = calibrate_kernel(nl->kernel, nl->material, dim, config.model.plane);
    const Eigen::MatrixXd& C0 = nl->material.C0;
    const bool partial_volume = config.nonlocal.horizon_edge == casefile::HorizonEdge::partial_volume;
    if (config.nonlocal.calibration == casefile::CalibrationRule::discrete) {
      if (!m.structure)
        throw InputError(fmt::format("{}: calibration = \"discrete\" needs a structured box mesh",
                                     config.nonlocal.where.describe()));
      nl->kernel.scale = nl->calibration.scale;
      nl->discrete_factor = assembly::discrete_calibration_factor(
          *m.structure, dim, config.nonlocal.quadrature, nl->kernel, C0, partial_volume);
      nl->calibration.scale *= nl->discrete_factor;
      nl->calibration.gc_factor *= nl->discrete_factor;
    }
    nl->kernel.scale = nl->calibration.scale / scale;  // bond weights W = t² w w carry t twice
  } else {
    std::vector<int> assigned(static_cast<std::size_t>(m.num_cells()), -1);
    for (const auto& mat : config.materials) {
      const int id =
          field.add_tensor(fem::reduce_stiffness(material_stiffness(mat), dim, config.model.plane));
      for (Index c : m.cell_sets.at(mat.region)) {
        field.set_cell(c, id);
        assigned[static_cast<std::size_t>(c)] = id;
      }
    }
    for (Index c = 0; c < m.num_cells(); ++c)
      if (assigned[static_cast<std::size_t>(c)] < 0)
        throw InputError(
            fmt::format("{}: cell {} (centroid {:.4g}, {:.4g}, {:.4g}) has no material; give a material "
                        "with region = \"all\" or cover every region",
                        config.path, window ? window->global_cell[static_cast<std::size_t>(c)] : c,
                        m.cell_centroid(c).x(), m.cell_centroid(c).y(), m.cell_centroid(c).z()));
    phase("dof map");
  }
  dofs::DofMap dofmap(m, dim);  // CG; with [nonlocal], place_alpha sets the CG/DG flags
  std::optional<DamageModel> damage;
  if (config.has_damage())
    damage = make_damage_model(config, m, rule, config.nonlocal.enabled ? config.nonlocal.quadrature : 0,
                               nl ? &full_C0 : nullptr);
  Discretization d{config,          std::move(m),      std::move(dofmap),
                   std::move(rule), std::move(field),  scale,
                   std::move(nl),   std::move(damage), {}};
  d.window = window;
  d.computed_cells = part.window ? partition::cells_near_part(d.mesh, part.window->owner, part.part)
                                 : partition::cells_near_part(d.mesh, part.parts, part.part);
  d.share_flags = std::move(part.share_flags);
  if (d.nonlocal) {
    if (part.window)
      place_alpha(d, make_alpha_field(config), phase, true,
                  {part.window->any_over_processes, std::pair{config.mesh.box.lower, config.mesh.box.upper}},
                  part.window->max_over_processes);
    else
      place_alpha(d, make_alpha_field(config), phase, true);
    if (window) window->half_bound = d.nonlocal->points.half_bound;
  }
  return d;
}

Discretization rebuild_for_alpha(const Discretization& disc, alpha::AlphaField alpha) {
  PERIMORPH_ASSERT(disc.nonlocal.has_value(), "rebuild_for_alpha needs a discretization with [nonlocal]");
  Discretization d = disc;
  place_alpha(
      d, std::move(alpha), [](const char*) {}, false);
  return d;
}

std::vector<Index> nodes_read(const Discretization& disc) {
  std::vector<Index> cells;
  for (Index c = 0; c < disc.mesh.num_cells(); ++c)
    if (disc.nonlocal ? disc.nonlocal->points.holds(c)
                      : disc.computed_cells.empty() || disc.computed_cells[static_cast<std::size_t>(c)])
      cells.push_back(c);
  return disc.dofmap.dof_nodes_of_cells(cells);
}

}  // namespace perimorph::setup
