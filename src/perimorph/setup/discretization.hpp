#pragma once
// The discretized problem built from a case file: mesh (with regions and
// pre-crack cuts), dof map, quadrature and the local stiffness at every
// quadrature point. This is where typed case data meets the pipeline stages.

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/nonlocal_assembly.hpp"
#include "perimorph/casefile/case_config.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/setup/damage_model.hpp"
#include "perimorph/setup/mesh_window.hpp"
#include "perimorph/setup/nonlocal_setup.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace perimorph::setup {

struct PieceNumbers;  // piece_model.hpp
struct PieceSource;   // piece_model.hpp

struct Discretization {
  casefile::CaseConfig config;
  mesh::Mesh mesh;
  dofs::DofMap dofmap;
  std::vector<fem::QuadraturePoint> rule;
  /// The local stiffness C(x) at d = 0: with [material.damage], the residual
  /// branch (morphed with α when [nonlocal]) plus d_c C₀ (THEORY §6); a run's
  /// damage lowers it by d C₀ (damaged_stiffness).
  fem::ConstitutiveField stiffness;
  double scale = 1.0;  ///< thickness (2D) or cross-section (1D)
  /// The non-local part, when the case has a [nonlocal] section. With
  /// [solver] operator = "matrix-free" its cell graph is the diagonal one
  /// (no bond is assembled; system/matrix_free_stiffness.hpp).
  std::optional<NonlocalModel> nonlocal;
  /// The local damage, when a material has [material.damage].
  std::optional<DamageModel> damage;
  /// The cells whose morphed C this process computed (1; empty: every cell).
  /// A process of a distributed run computes those of its part and their
  /// neighbours through a mesh node (partition::cells_near_part): every cell
  /// whose local stiffness, strain or stress it assembles or writes. With
  /// [nonlocal], elsewhere `stiffness` holds NaN, so that a read of it shows.
  /// The cell graph holds their rows only. The CG/DG flags and α at the
  /// local points are those of every cell, on every process: a process decides
  /// the flags of the cells it computes and gets the others' through
  /// `share_flags` (ModelPart).
  std::vector<char> computed_cells;
  /// ModelPart::share_flags, kept for a rebuild (empty for the whole model).
  std::function<std::vector<char>(std::vector<char>)> share_flags{};
  /// On a process's piece of the model (cut_to_piece): whether a condition
  /// holds on any process (collective; la::). A set may reach none of a
  /// piece's dofs, and is an error only when it reaches none on every
  /// process (set_dof_nodes). Empty for a mesh that is the whole model's.
  std::function<bool(bool)> any_over_processes{};
  /// On a process's piece of the model (cut_to_piece): what its local cells,
  /// nodes and dof nodes are in the whole model, and the part of each cell.
  /// Null for a mesh that is the whole model's.
  std::shared_ptr<const PieceNumbers> piece{};
  /// On a process's piece of a run with [adaptivity]: the part it was cut
  /// from, kept for a rebuild for a grown α (rebuild_piece_for_alpha). Null
  /// otherwise.
  std::shared_ptr<const PieceSource> source{};
  /// On a part built on a window of a box mesh (ModelPart::window): what its
  /// cells and nodes are in the whole mesh. Null for a mesh that is the whole
  /// mesh or a piece.
  std::shared_ptr<const WindowNumbers> window{};

  int dim() const { return mesh.dim(); }
  assembly::LocalSpace local_space() const { return {mesh, dofmap, rule, scale}; }
  /// The non-local space (requires [nonlocal]), `failed` bonds left out (null: none).
  assembly::NonlocalSpace nonlocal_space(const bonds::BrokenBonds* failed = nullptr) const {
    assembly::NonlocalSpace s{mesh, dofmap, nonlocal->points, nonlocal->graph, nonlocal->kernel};
    s.alpha = &nonlocal->alpha;
    s.scale = scale;
    s.broken = failed;
    s.cuts = &nonlocal->cuts;
    return s;
  }
  /// True if cell c carries local stiffness: not purely non-local, or
  /// purely non-local with the damageable branch (d_c − d) C₀ of THEORY §6
  /// (not on a DG degree 0 cell, whose one node has no strain).
  bool has_local_stiffness(Index c) const {
    if (!nonlocal || !nonlocal->morph.purely_nonlocal[static_cast<std::size_t>(c)]) return true;
    return damage && damage->law_of(c) >= 0 && dofmap.cell_nodes(c).size() > 1;
  }
};

/// The mesh of a case: box, regions (cell sets and region ids), cuts, then
/// [[node_set]] node sets (so both copies of a split node are selected);
/// throws InputError for a cut off the element faces, an empty region or a
/// node set that selects no node.
mesh::Mesh build_mesh(const casefile::CaseConfig& config);

/// build_mesh's holes, regions, cuts and node sets applied to `m`: the case's
/// whole mesh, or a window of its box (no hole or cut; window_mesh) whose
/// checks ask every process through `whole` (collective then).
mesh::Mesh shape_mesh(const casefile::CaseConfig& config, mesh::Mesh m, const WholeMeshChecks& whole = {});

/// 3D stiffness (Voigt 6×6) of a case material, checked for admissibility.
Voigt6 material_stiffness(const casefile::MaterialSpec& m);

/// Called with the name of each set-up phase as it begins ("mesh", "bond
/// graph", ...), for a progress display.
using PhaseCallback = std::function<void(const std::string& phase)>;

/// Throws InputError, naming the [solver] `operator` key and the reason, for a
/// case with operator = "matrix-free" that the matrix-free operator does not
/// cover (it needs a box grid without holes or cuts, [nonlocal] with
/// discretization = "discontinuous-constant", α ≡ 1, no fracture, damage or
/// adaptivity). Called by build_discretization.
void check_matrix_free(const casefile::CaseConfig& config);

/// The part of the model a process builds: part `part` of `parts`
/// (coordinate bisection of the cells; one part: the whole model).
struct ModelPart {
  int parts = 1;
  int part = 0;
  /// With several parts, required: the elementwise maximum of a flag per
  /// cell over the processes building the parts (collective; la::). The
  /// purely non-local (CG/DG) flags a process does not decide (its cells far
  /// from the part) come from the process whose part holds them.
  std::function<std::vector<char>(std::vector<char>)> share_flags{};
  /// With several parts, optional: build the part on this window of a box
  /// mesh (no hole or cut) instead of the whole mesh; `share_flags` then
  /// takes and gives the window's flags. Every cell whose morphed C, graph
  /// row or points the part computes must be in it (setup::part_window).
  std::optional<MeshWindow> window{};
};

/// Builds everything; throws InputError naming the case-file key for problems
/// found only now (a cut off the element faces, an inadmissible material, a
/// cell left without material, an [[alpha.region]] that reaches no
/// quadrature point). `on_phase`, if given, hears each phase begin. With
/// several parts, the morphed C of the cells near `part` only
/// (Discretization::computed_cells) and the flags of those cells, the others'
/// shared (collective); the rest is whole.
Discretization build_discretization(const casefile::CaseConfig& config, const PhaseCallback& on_phase = {},
                                    ModelPart part = {});

/// The dof nodes (ascending) whose displacement this process reads: those of
/// the cells whose non-local points it stores (NonlocalPoints::holds: its
/// stretch pass reaches them), or without [nonlocal] of its computed_cells.
/// They hold every cell its part writes, strains or assembles and every dof
/// node it owns. Every node for the whole model.
std::vector<Index> nodes_read(const Discretization& disc);

/// The discretization of `disc`'s case with α replaced by `alpha` (THEORY §5:
/// α grows during a run). Kept: the mesh, the local quadrature, the material
/// and the calibrated kernel. Rebuilt from the new α: the non-local points,
/// the cell graph, the morphed C, the CG/DG flags and the dof map. What
/// outlives it keeps its key: cells, non-local points (their number and
/// positions per cell do not depend on α) and quadrature points, so a run's
/// failed bonds (bonds::BrokenBonds) and history carry over; dofs change where
/// cells switch between CG and DG. Equals build_discretization of the case
/// with that α, and computes the same cells' C (computed_cells). Requires
/// [nonlocal].
Discretization rebuild_for_alpha(const Discretization& disc, alpha::AlphaField alpha);

}  // namespace perimorph::setup
