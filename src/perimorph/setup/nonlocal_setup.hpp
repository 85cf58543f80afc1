#pragma once
// Setting up the non-local part of a case (THEORY §1–§4): the calibrated
// micromodulus, the α field, the non-local quadrature points, the cell graph
// and the morphed local stiffness. Case data in, pipeline objects out.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/assembly/morphed_stiffness.hpp"
#include "perimorph/bonds/cell_graph.hpp"
#include "perimorph/bonds/cut_neighborhood.hpp"
#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/casefile/case_config.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"
#include "perimorph/setup/mesh_window.hpp"
#include "perimorph/setup/nonlocal_material.hpp"

#include <span>

namespace perimorph::setup {

struct NonlocalModel {
  NonlocalMaterial material;  ///< the material, resolved for central forces
  peridynamics::Micromodulus kernel;
  peridynamics::Calibration calibration;  ///< scale includes discrete_factor
  double discrete_factor = 1.0;           ///< discrete calibration factor (1: continuum calibration)
  alpha::AlphaField alpha = alpha::AlphaField::constant(0.0);
  bonds::NonlocalPoints points;
  /// On a model part (Discretization::computed_cells), the rows of the
  /// computed cells only, the others empty: every row a process reads.
  bonds::CellGraph graph;
  bonds::CutNeighborhood cuts;  ///< the mesh's cuts near each cell, for bonds of points.bond_reach
  assembly::MorphedStiffness morph;
};

/// The α profile of a case-file name.
alpha::Profile alpha_profile(casefile::AlphaProfile p);

/// The α field of a case (α ≡ 0 when [alpha] is absent).
alpha::AlphaField make_alpha_field(const casefile::CaseConfig& config);

/// Throws InputError, naming the entry's file and line, its shape and the
/// mesh's extent, for an [[alpha.region]] of `alpha` (made by make_alpha_field)
/// that gives α > 0 at none of the points α is read at: the non-local points
/// and the local quadrature points of `rule` in every cell. Such a region
/// would change nothing. On a window of the mesh `whole` asks every process
/// (collective).
void check_alpha_regions(const casefile::CaseConfig& config, const alpha::AlphaField& alpha,
                         const bonds::NonlocalPoints& points, const mesh::Mesh& mesh,
                         std::span<const fem::QuadraturePoint> rule, const WholeMeshChecks& whole = {});

/// The micromodulus of a case (shape, δ, l; scale not yet calibrated).
peridynamics::Micromodulus make_kernel(const casefile::NonlocalSpec& spec);

}  // namespace perimorph::setup
