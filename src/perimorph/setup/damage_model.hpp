#pragma once
// The local damage of a case (THEORY §6) as the discretization holds it: the
// law of each damageable material, its undamaged stiffness C₀, which cells
// it acts on, and where a non-local point reads the damage. The stiffness
// field of the discretization (Discretization::stiffness) is the undamaged
// one, residual branch (morphed with α) plus d_c C₀; the damage history of
// a run (RunState::history: d at every local quadrature point) lowers it by
// d C₀ point by point (damaged_stiffness).

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/damage_law.hpp"
#include "perimorph/fem/quadrature.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
}

namespace perimorph::setup {

struct DamageModel {
  std::vector<fem::DamageLaw> laws;  ///< one per damageable material
  std::vector<Eigen::MatrixXd> C0;   ///< each law's undamaged stiffness (model dimension, Voigt)
  std::vector<int> cell_law;         ///< per cell: index into laws, −1 for a cell that cannot damage
  int points_per_cell = 0;           ///< local quadrature points per cell (history stride)
  /// Non-local point q of any cell (same reference rule in every cell) → the
  /// local quadrature point of that cell nearest to it, whose d it reads.
  std::vector<int> local_point_of;

  int law_of(Index c) const { return cell_law[static_cast<std::size_t>(c)]; }
  /// d at local point q of cell c in `history`.
  static double at(std::span<const double> history, Index c, int q, int npts) {
    return history[static_cast<std::size_t>(c) * static_cast<std::size_t>(npts) +
                   static_cast<std::size_t>(q)];
  }
  /// True if non-local point p of cell c has reached its law's d_c (a cell
  /// that cannot damage: true, nothing holds its bonds back). THEORY §6: a
  /// bond may fail only where the damage has reached d_c.
  bool critical(std::span<const double> history, Index c, int p) const;
};

/// The damage model of `config` on `mesh` (cells of each material from its
/// region, later materials winning as for the stiffness), with `rule` the
/// local quadrature and `nonlocal_points_per_direction` the non-local rule
/// (0: no non-local model). C0[k] is the material's full stiffness reduced to
/// the model's dimension; with [nonlocal], `nonlocal_C0` is the one material's
/// as resolved for central forces (setup::NonlocalMaterial::C0, unscaled).
DamageModel make_damage_model(const casefile::CaseConfig& config, const mesh::Mesh& mesh,
                              std::span<const fem::QuadraturePoint> rule, int nonlocal_points_per_direction,
                              const Eigen::MatrixXd* nonlocal_C0 = nullptr);

/// `undamaged` lowered by d C₀ at every local point of every damageable cell
/// with d > 0 (`history`: d per cell and local point); cells without damage
/// keep their shared tensors.
fem::ConstitutiveField damaged_stiffness(const fem::ConstitutiveField& undamaged, const DamageModel& damage,
                                         std::span<const double> history);

}  // namespace perimorph::setup
