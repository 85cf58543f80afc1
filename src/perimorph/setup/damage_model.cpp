#include "perimorph/setup/damage_model.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/fem/material.hpp"
#include "perimorph/mesh/mesh.hpp"
#include "perimorph/setup/discretization.hpp"

#include <limits>

namespace perimorph::setup {

bool DamageModel::critical(std::span<const double> history, Index c, int p) const {
  const int law = law_of(c);
  if (law < 0) return true;
  const double d = at(history, c, local_point_of[static_cast<std::size_t>(p)], points_per_cell);
  return d >= laws[static_cast<std::size_t>(law)].d_c;
}

DamageModel make_damage_model(const casefile::CaseConfig& config, const mesh::Mesh& mesh,
                              std::span<const fem::QuadraturePoint> rule, int nonlocal_points_per_direction,
                              const Eigen::MatrixXd* nonlocal_C0) {
  DamageModel out;
  const int dim = mesh.dim();
  out.points_per_cell = static_cast<int>(rule.size());
  out.cell_law.assign(static_cast<std::size_t>(mesh.num_cells()), -1);
  for (const auto& mat : config.materials) {
    int law = -1;
    if (mat.damage.enabled) {
      law = static_cast<int>(out.laws.size());
      out.laws.push_back({mat.damage.k0, mat.damage.k1, mat.damage.d_c});
      out.C0.push_back(nonlocal_C0 ? *nonlocal_C0
                                   : Eigen::MatrixXd(fem::reduce_stiffness(material_stiffness(mat), dim,
                                                                           config.model.plane)));
    }
    // Later materials win, as for the stiffness (build_discretization).
    for (Index c : mesh.cell_sets.at(mat.region)) out.cell_law[static_cast<std::size_t>(c)] = law;
  }
  if (nonlocal_points_per_direction > 0)
    for (const auto& p : fem::gauss_legendre(dim, nonlocal_points_per_direction)) {
      int best = 0;
      double best_d2 = std::numeric_limits<double>::infinity();
      for (std::size_t q = 0; q < rule.size(); ++q) {
        const double d2 = (rule[q].xi - p.xi).squaredNorm();
        if (d2 < best_d2) {
          best_d2 = d2;
          best = static_cast<int>(q);
        }
      }
      out.local_point_of.push_back(best);
    }
  return out;
}

fem::ConstitutiveField damaged_stiffness(const fem::ConstitutiveField& undamaged, const DamageModel& damage,
                                         std::span<const double> history) {
  fem::ConstitutiveField out = undamaged;
  const int npts = undamaged.points_per_cell();
  PERIMORPH_ASSERT(npts == damage.points_per_cell, "damage history and stiffness field disagree");
  std::vector<Eigen::MatrixXd> C(static_cast<std::size_t>(npts));
  for (Index c = 0; c < undamaged.num_cells(); ++c) {
    const int law = damage.law_of(c);
    if (law < 0) continue;
    bool damaged = false;
    for (int q = 0; q < npts && !damaged; ++q) damaged = DamageModel::at(history, c, q, npts) > 0.0;
    if (!damaged) continue;
    for (int q = 0; q < npts; ++q)
      C[static_cast<std::size_t>(q)] = undamaged.matrix(c, q) - DamageModel::at(history, c, q, npts) *
                                                                    damage.C0[static_cast<std::size_t>(law)];
    out.set_cell_points(c, C);
  }
  return out;
}

}  // namespace perimorph::setup
