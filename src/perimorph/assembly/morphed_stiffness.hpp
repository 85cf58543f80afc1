#pragma once
// The morphed local stiffness at the local quadrature points (THEORY §3,
// eq. 2.28):
//
//   C(x) = (1 − α(x)) C₀ + ∫_{H(x)} c(ξ) (α(x) − α(p))/2 · ξ⊗ξ⊗ξ⊗ξ / (2|ξ|²) dp
//
// with the horizon integral evaluated on the non-local quadrature points (so
// C = C₀ exactly where α ≡ 0 on the horizon and C = 0 exactly where α ≡ 1), or
// the rough "partition" rule C = (1 − α(x)) C₀ (eq. 2.46) for comparison.

#include "perimorph/alpha/alpha_field.hpp"
#include "perimorph/fem/quadrature.hpp"
#include "perimorph/peridynamics/micromodulus.hpp"

#include <Eigen/Core>

#include <functional>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}
namespace perimorph::bonds {
struct NonlocalPoints;
struct CellGraph;
}  // namespace perimorph::bonds
namespace perimorph::fem {
class ConstitutiveField;
}

namespace perimorph::assembly {

enum class CouplingRule { morphing, partition };

struct MorphedStiffness {
  /// 1 where α = 1 and C = 0 at every local point of the cell: a purely
  /// non-local cell (where α < 1 at a point, C keeps (1 − α) C₀ there).
  std::vector<char> purely_nonlocal;
  /// Cells whose C varies point by point (the morphing zone), of those computed.
  Index morphing_cells = 0;
};

/// The image of the reference point xi of cell c under the Q1 map.
Vec3 physical_point(const mesh::Mesh& mesh, Index c, const Vec3& xi);

/// α at the local point xi of cell c: the value morph_stiffness uses there
/// (computed where it is needed, not stored: the same bits on every call).
double alpha_at_local_point(const mesh::Mesh& mesh, const alpha::AlphaField& alpha, Index c, const Vec3& xi);

/// The horizon integral ∫ c(ξ) (α_g − α(p))/2 ξ⊗ξ⊗ξ⊗ξ/(2|ξ|²) dp at x_g
/// (Voigt, model dimension), summed over the non-local points of the given
/// cells, bonds crossing a cut excluded, with the same bond rule as the
/// non-local stiffness (with points.partial_volume(), `half_g` is the box of
/// x_g). Exposed for tests.
Eigen::MatrixXd horizon_integral(const Vec3& xg, double alpha_g, std::span<const Index> cells,
                                 const bonds::NonlocalPoints& points,
                                 const peridynamics::Micromodulus& kernel, const mesh::Mesh& mesh,
                                 const Vec3& half_g = Vec3::Zero());

/// Fills `field` (sized for `rule`) with C(x) for every cell marked in
/// `computed` (every cell if empty), from the reference stiffness C0 (Voigt,
/// model dimension); the other cells get NaN, unless purely non-local (0).
/// The purely non-local flags are
/// decided for the computed cells (C = 0 and α = 1 at every local point) and
/// the others' are 0 until `share_flags` (required with `computed`: the
/// elementwise maximum over the processes, collective) brings them from the
/// processes that compute them, every cell being computed by one. `graph`
/// must hold, for each computed cell, every cell within the horizon; the
/// other cells' rows are not read.
MorphedStiffness morph_stiffness(const mesh::Mesh& mesh, std::span<const fem::QuadraturePoint> rule,
                                 const bonds::NonlocalPoints& points, const bonds::CellGraph& graph,
                                 const peridynamics::Micromodulus& kernel, const alpha::AlphaField& alpha,
                                 const Eigen::MatrixXd& C0, CouplingRule rule_kind,
                                 fem::ConstitutiveField& field, std::span<const char> computed = {},
                                 const std::function<std::vector<char>(std::vector<char>)>& share_flags = {});

}  // namespace perimorph::assembly
