#pragma once
// The typed form of a case file. Parsed once, at the boundary, by
// parse_case_file (parse_case.hpp); nothing else reads TOML. Every field has
// passed validation when a CaseConfig exists: later stages may rely on it.
// The format is documented in docs/case-file.md.

#include "perimorph/casefile/run_spec.hpp"
#include "perimorph/casefile/source_location.hpp"
#include "perimorph/core/hole.hpp"
#include "perimorph/core/types.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace perimorph::casefile {

/// [mesh] type = "box". `dim` is the case's dimension for every mesh type.
struct BoxMesh {
  int dim = 3;
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Ones();
  std::array<Index, 3> cells{1, 1, 1};
};

/// [[mesh.cut]]: 1D at = x; 2D from/to (a segment); 3D origin, edge1, edge2
/// (a parallelogram).
struct CutSpec {
  Vec3 origin = Vec3::Zero();
  Vec3 edge1 = Vec3::Zero();
  Vec3 edge2 = Vec3::Zero();
  SourceLocation where;
};

/// [[mesh.hole]]: the cells whose centroid lies strictly inside the shape are
/// removed. disk (2D): center, radius; ball (3D): center, radius; cylinder
/// (3D, axis along z through center): center, radius; box (any dim): lower,
/// upper (upper > lower).
struct HoleSpec {
  HoleShape shape = HoleShape::disk;
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
  SourceLocation where;
};

enum class MeshKind { box, gmsh };

/// [mesh] type = "gmsh": a mesh file read through Gmsh's library
/// (mesh/gmsh_reader.hpp), its physical groups as named sets.
struct GmshMesh {
  std::string file;  ///< as given, made relative to the case file's folder
  /// Face groups (physical curves in 2D, surfaces in 3D) split as pre-cracks
  /// (mesh::split_along_faces): [mesh] precrack = "name" or ["a", "b"].
  std::vector<std::string> precracks;
  SourceLocation where;           ///< the `file` key
  SourceLocation precrack_where;  ///< the `precrack` key
};

struct MeshSpec {
  MeshKind kind = MeshKind::box;
  BoxMesh box;    ///< type = "box" (only box.dim, the dimension, for "gmsh")
  GmshMesh gmsh;  ///< type = "gmsh"
  std::vector<HoleSpec> holes;
  std::vector<CutSpec> cuts;
};

/// [[region]]: the cells whose centroid lies in a box (lower, upper), or the
/// cells of a cell set of the mesh (`set`, e.g. a Gmsh physical surface or
/// volume; then lower and upper are unused).
struct RegionSpec {
  std::string name;
  int id = 0;  ///< 1, 2, ... in order of appearance; 0 is the rest of the mesh
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
  std::string set;  ///< non-empty: the region is this mesh cell set
  SourceLocation where;
};

/// [[node_set]]: the mesh nodes x with lower - tol <= x <= upper + tol on
/// every axis (tol = 1e-9 × the mesh's largest extent), selected when the mesh
/// is built; both copies of a node split by a cut. upper >= lower (equal
/// bounds: a plane, line or point). The name is unique and is no mesh set's
/// (xmin, ..., boundary, all) or region's.
struct NodeSetSpec {
  std::string name;
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();
  SourceLocation where;
};

using PlaneMode = perimorph::PlaneMode;

/// [model]
struct ModelSpec {
  PlaneMode plane = PlaneMode::strain;  ///< 2D only
  double thickness = 1.0;               ///< 2D: out-of-plane thickness; 1D: cross-section area
  int local_quadrature = 2;             ///< Gauss points per direction for the local stiffness
};

enum class MaterialKind { isotropic, orthotropic, transversely_isotropic };

/// How a material that central forces cannot represent is treated ([nonlocal]
/// only): exact = a given value inconsistent with the Cauchy relations is an
/// error; nearest = the stiffness is replaced by its nearest central-force
/// tensor (the physics layer applies both).
enum class CauchyRule { exact, nearest };

/// [material.damage]: the local damage law of THEORY §6 on this material
/// (isotropic only). The stiffness splits into a residual branch (1 − d_c) C₀
/// and a damageable one (d_c − d) C₀; d grows with the damage force
/// Y = ½ ε : C₀ : ε past the threshold k0 + k1 d, irreversibly, up to d_c.
/// With [nonlocal], the non-local micromodulus is calibrated to the residual
/// branch and bonds may fail only where d = d_c.
struct DamageSpec {
  bool enabled = false;  ///< the table is present
  double k0 = 0.0;       ///< damage-force threshold at onset (stress units), ≥ 0
  double k1 = 0.0;       ///< hardening modulus of the threshold (stress units), > 0
  /// Critical damage, 0 < d_c ≤ 1: where the local model stops (localization).
  /// d_c < 1 hands the residual branch to the non-local model where reached;
  /// with [nonlocal], d_c < 1 (d_c = 1 would leave it no stiffness).
  double d_c = 1.0;
  SourceLocation where;  ///< the [material.damage] header
};

/// [[material]]: assigned to a region ("all" = every cell not claimed by a
/// later material). Parsed by parse_material.cpp.
///
/// Isotropic: E, nu. `nu`: with [nonlocal] it may be left out and is then NaN
/// (the physics layer takes the central-force value, 1/4 or 1/3, and checks a
/// given one against it); a given nu satisfies -1 < nu < 0.5.
///
/// Orthotropic (kind orthotropic) and transversely isotropic (kind
/// transversely_isotropic, axis e3) in material axes; the axes are the columns
/// of `axes` (from `rotation`, see docs). Orthotropic input is either
/// engineering constants (E1 ... G23; by_stiffness false) or stiffness
/// components (by_stiffness true; `stiffness` holds them). Transversely
/// isotropic input (E_in, E_axis, nu_axial, nu_in, G_axial) fills the
/// engineering fields: E1 = E2 = E_in, E3 = E_axis, nu12 = nu_in, nu13 = nu23
/// = nu_axial, G12 = E_in / (2 (1 + nu_in)), G13 = G23 = G_axial. Convention
/// nuij / Ei = nuji / Ej. A given compliance (engineering) or stiffness normal
/// block is positive definite and given moduli are positive.
struct MaterialSpec {
  std::string name;
  std::string region = "all";
  MaterialKind kind = MaterialKind::isotropic;
  double E = 0.0, nu = 0.0;
  /// Isotropic: where `nu` is (key 'material[k].nu'), for messages about it;
  /// if nu was left out, the material's header with that key.
  SourceLocation nu_where;
  /// Engineering constants. G12, G13, G23 are NaN when left out (only allowed
  /// with [nonlocal]); transversely isotropic: nu12 (= nu_in) and G12 are NaN
  /// when nu_in is left out (only allowed with [nonlocal]). by_stiffness: E1,
  /// E2, E3, nu12, nu13, nu23 are derived from the inverse of the normal block
  /// of `stiffness`, and G23 = C2323, G13 = C1313, G12 = C1212 (NaN if left out).
  double E1 = 0.0, E2 = 0.0, E3 = 0.0, nu12 = 0.0, nu13 = 0.0, nu23 = 0.0, G12 = 0.0, G13 = 0.0, G23 = 0.0;
  /// Orthotropic given by its stiffness components in material axes instead of engineering constants.
  bool by_stiffness = false;
  /// by_stiffness: Voigt 6x6 in material axes (order xx, yy, zz, yz, xz, xy): C(0,0)=C1111, C(1,1)=C2222,
  /// C(2,2)=C3333, C(0,1)=C(1,0)=C1122, C(0,2)=C(2,0)=C1133, C(1,2)=C(2,1)=C2233, C(3,3)=C2323,
  /// C(4,4)=C1313, C(5,5)=C1212, all other entries 0. A shear entry left out (only allowed with
  /// [nonlocal]) is NaN. Zero unless by_stiffness.
  Voigt6 stiffness = Voigt6::Zero();
  /// Where each shear value came from, for messages: index 0 = G23 or C2323 (transversely isotropic:
  /// G_axial), 1 = G13 or C1313 (G_axial), 2 = G12 or C1212 (nu_in when given, else the material
  /// header). Left out: the material's header with that key name ('material[k].G12'). Isotropic:
  /// unset.
  /// (The explicit initializer keeps GCC 12's -Wrestrict false positive on std::string assignments
  /// near a MaterialSpec copy quiet.)
  std::array<SourceLocation, 3> shear_where = {SourceLocation{}, SourceLocation{}, SourceLocation{}};
  CauchyRule cauchy = CauchyRule::exact;
  /// The `cauchy` key; when absent, the material's header with that key name ('material[k].cauchy').
  SourceLocation cauchy_where;
  Mat3 axes = Mat3::Identity();
  DamageSpec damage;  ///< [material.damage]; enabled = false: elastic
  SourceLocation where;
};

enum class KernelKind { constant, conical, exponential, gaussian, pmb };
enum class Discretization { continuous, discontinuous, discontinuous_constant };
enum class Coupling { morphing, partition };
enum class CalibrationRule { continuum, discrete };
/// How bonds at the horizon's edge are weighed: a bond counts iff |ξ| < δ
/// (cutoff), or by the fraction of its points' boxes inside the horizon
/// (partial_volume, peridynamics/horizon_edge.hpp).
enum class HorizonEdge { cutoff, partial_volume };

/// [nonlocal]: the bond-based peridynamic model (THEORY §1, §2, §4). Its
/// micromodulus is calibrated from the local isotropic material. Parsed by
/// parse_nonlocal.cpp; `where` is the [nonlocal] header.
struct NonlocalSpec {
  bool enabled = false;  ///< the section is present
  KernelKind kernel = KernelKind::constant;
  double horizon = 0.0;  ///< δ > 0
  double length = 0.0;   ///< l > 0 (exponential, gaussian only)
  int quadrature = 4;    ///< Gauss points per direction of the non-local double integral
  /// Elements used where the model is purely non-local (local stiffness ≡ 0):
  /// continuous (CG), discontinuous (DG, private vertex nodes) or
  /// discontinuous_constant (DG degree 0: one node per element).
  Discretization discretization = Discretization::continuous;
  Coupling coupling = Coupling::morphing;
  /// continuum: ĉ from the closed forms of THEORY §2; discrete: ĉ further
  /// scaled so that the bulk tensor summed with the actual non-local
  /// quadrature on the (structured) grid matches C₀ in the least-squares sense.
  CalibrationRule calibration = CalibrationRule::continuum;
  HorizonEdge horizon_edge = HorizonEdge::cutoff;
  SourceLocation where;
};

enum class AlphaShapeKind { interval, slab, ball, cylinder, box };
enum class AlphaProfile { heaviside, linear, cubic };

/// [[alpha.region]]: α = 1 inside the shape, profile(1 − d/transition) at
/// distance d < transition outside it, 0 beyond (THEORY §3.1). Only the
/// fields of `shape` are set; vector components beyond mesh.dim are 0.
/// `where` is the entry's [[alpha.region]] header.
struct AlphaRegionSpec {
  /// interval: 1D only; cylinder: 3D only.
  AlphaShapeKind shape = AlphaShapeKind::ball;
  Vec3 point = Vec3::Zero();       ///< ball centre (`center`), cylinder and slab `point`
  Vec3 direction = Vec3::UnitZ();  ///< slab `normal`, cylinder `axis`: normalized (given non-zero)
  double radius = 0.0;             ///< ball, cylinder: > 0
  double half_width = 0.0;         ///< slab: ≥ 0
  /// interval: lower.x() < upper.x() (finite); box: lower < upper on each
  /// axis, components may be -inf / +inf.
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();
  double transition = 0.0;  ///< width L ≥ 0
  AlphaProfile profile = AlphaProfile::cubic;
  SourceLocation where;
};

/// [alpha]: either a constant `value` in [0, 1] or regions (α = max over them),
/// never both. Absent: α ≡ 0 (value 0, no regions); present only with
/// [nonlocal]. `where` is the [alpha] header (the first [[alpha.region]]
/// header when there is no [alpha] line).
struct AlphaSpec {
  double value = 0.0;
  std::vector<AlphaRegionSpec> regions;
  SourceLocation where;
};

/// Which of the bonds over the criterion break in one iteration of the
/// implicit loop (THEORY §5): all of them (the thesis' choice), or only those
/// whose stretch ratio s/s_crit is within `fraction` of the largest one.
enum class BreakRule { all, fraction };

/// [fracture]: bond failure by critical stretch (THEORY §5; needs [nonlocal]).
/// Exactly one of s_crit and G_c is given; with G_c, s_crit follows from the
/// bulk closed form G_c = κ s_crit² (THEORY §5 table) of the calibrated kernel.
struct FractureSpec {
  bool enabled = false;  ///< the section is present
  double s_crit = 0.0;   ///< > 0, or 0 when G_c is given
  double G_c = 0.0;      ///< > 0, or 0 when s_crit is given
  BreakRule rule = BreakRule::all;
  double fraction = 1.0;  ///< rule = fraction: 0 < fraction ≤ 1
  /// Bond-breaking iterations per increment, ≥ 1. The default is a guard no
  /// real crack reaches (docs/case-file.md: ~9 per cell of crack path).
  int max_iterations = 10000;
  /// Names of [[region]]s whose bonds never fail: a bond with either end in
  /// one of their cells is kept (a no-fail zone, e.g. under a load patch).
  std::vector<std::string> no_fail;
  /// Whether a bond between two points of the same cell may fail. A Q1 cell
  /// (CG or DG) cannot carry a discontinuity, so such failures only smear the
  /// crack over the cell; with false, cracks open only between DG cells, as in
  /// the thesis ("when DGFEM is used, cracks can propagate only at interfaces
  /// between elements", §3.3.5).
  bool intra_cell_failure = true;
  SourceLocation where;  ///< the [fracture] header
};

/// Where the adaptive step grows α (THEORY §5): after the bond-breaking loop
/// of an increment has settled (the thesis' choice), or after every
/// bond-breaking iteration.
enum class AdaptivityUpdate { increment, iteration };

/// [adaptivity]: the non-local zone grows with the crack (THEORY §5, thesis
/// §3.3.4). Every cell holding a newly failed bond adds a ball (disk in 2D)
/// centred on its centroid: α = 1 to radius h_e + core, falling by `profile`
/// to 0 at h_e + core + transition (h_e the cell's longest edge); α never
/// decreases. With the predictor, a cell not yet at α = 1 whose strain
/// stretches some direction beyond theta · s_crit gets its ball before any of
/// its bonds fails. Needs [nonlocal] and [fracture]; parsed by
/// parse_adaptivity.cpp; `where` is the [adaptivity] header.
struct AdaptivitySpec {
  bool enabled = false;      ///< the section is present and enabled ≠ false
  double core = -1.0;        ///< ≥ 0; default (negative here): the horizon δ
  double transition = -1.0;  ///< ≥ 0; default (negative here): the horizon δ
  AlphaProfile profile = AlphaProfile::cubic;
  AdaptivityUpdate update = AdaptivityUpdate::increment;
  /// After α grew at the end of an increment: re-solve at the same load and
  /// run the bond-breaking loop again on the grown model (true), or go on to
  /// the next increment with it (false).
  bool redo = true;
  bool predictor = false;
  double theta = 0.8;  ///< predictor threshold, 0 < theta ≤ 1, of s_crit
  SourceLocation where;
};

/// [damage]: the nonlinear solve of an increment with local damage (THEORY
/// §6): fixed-point (secant) iterations {solve with the stiffness of the
/// current d; update d from the solution} until no quadrature point's d
/// changes by more than `tolerance` (absolute). Needs a material with
/// [material.damage]; optional (defaults below) when one has it. With
/// solver = newton, each update is preceded by a Newton solve (consistent
/// tangent, PETSc SNES, options prefix -damage_) for the d that the
/// current increment converges to, so the fixed point starts there.
enum class DamageSolver { secant, newton };

struct DamageSolverSpec {
  DamageSolver solver = DamageSolver::secant;
  double tolerance = 1e-6;  ///< > 0 (d is dimensionless, 0 … d_c)
  int max_iterations =
      500;  ///< ≥ 1 damage updates per increment; more stops the run, keeping what was computed
  SourceLocation where;  ///< the [damage] header (empty when absent)
};

struct CaseConfig {
  std::string path;   ///< the case file as given
  std::string text;   ///< its text as parsed (a restart compares it, casefile/case_values.hpp)
  std::string title;  ///< optional [case] title
  MeshSpec mesh;
  std::vector<RegionSpec> regions;
  std::vector<NodeSetSpec> node_sets;
  ModelSpec model;
  std::vector<MaterialSpec> materials;
  std::vector<DirichletSpec> dirichlet;
  std::vector<TractionSpec> tractions;
  LoadingSpec loading;
  SolverSpec solver;
  OutputSpec output;
  NonlocalSpec nonlocal;
  AlphaSpec alpha;
  FractureSpec fracture;
  AdaptivitySpec adaptivity;
  DamageSolverSpec damage;
  /// True if some material has [material.damage].
  bool has_damage() const {
    for (const auto& m : materials)
      if (m.damage.enabled) return true;
    return false;
  }
  int dim() const { return mesh.box.dim; }
};

}  // namespace perimorph::casefile
