#include "perimorph/evolution/cell_mechanisms.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"

#include <fmt/format.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace perimorph::evolution {

namespace {

constexpr double null_tolerance = 1e-10;  ///< of the largest reference diagonal on the cell

}  // namespace

CellMechanisms find_cell_mechanisms(const setup::Discretization& model, const la::Matrix& A,
                                    std::span<const double> reference_diagonal, std::span<const Index> cells,
                                    std::span<const Index> held, std::span<const double> force) {
  const int dim = model.dim();
  const auto& dm = model.dofmap;
  std::vector<Index> excluded(held.begin(), held.end());
  CellMechanisms out;
  std::vector<Index> dofs;
  for (Index c : cells) {
    dofs.clear();
    for (Index node : dm.cell_nodes(c))
      for (int d = 0; d < dim; ++d) {
        const Index dof = node * dim + d;
        if (!std::binary_search(excluded.begin(), excluded.end(), dof)) dofs.push_back(dof);
      }
    if (dofs.empty()) continue;
    double scale = 0.0;
    for (Index d : dofs) scale = std::max(scale, std::abs(reference_diagonal[static_cast<std::size_t>(d)]));
    const Eigen::MatrixXd block = A.block(dofs);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (block + block.transpose()));
    const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
    Eigen::Index k = 0;
    while (k < lambda.size() && lambda[k] <= null_tolerance * scale) ++k;
    if (k == 0) continue;
    const Eigen::MatrixXd modes = eig.eigenvectors().leftCols(k);  // orthonormal columns
    if (!force.empty()) {
      Eigen::VectorXd f(static_cast<Eigen::Index>(dofs.size()));
      for (std::size_t a = 0; a < dofs.size(); ++a)
        f[static_cast<Eigen::Index>(a)] = force[static_cast<std::size_t>(dofs[a])];
      const double work = (modes.transpose() * f).norm();
      if (work > 1e-10 * f.norm() && work > 0.0) {
        const Vec3 x = model.mesh.cell_centroid(c);
        throw Error(fmt::format(
            "bond failures have left a motion of the cell at ({:g}, {:g}, {:g}) that no intact bond resists, "
            "and the applied forces on its nodes do work on it: there is no quasi-static equilibrium",
            x.x(), x.y(), x.z()));
      }
    }
    // The dofs of the k largest pivots of modesᵀ: the modes restricted to them are invertible.
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(modes.transpose());
    std::vector<Index> pins;
    for (Eigen::Index j = 0; j < k; ++j)
      pins.push_back(dofs[static_cast<std::size_t>(qr.colsPermutation().indices()[j])]);
    ++out.cells;
    out.modes += static_cast<std::size_t>(k);
    for (Index p : pins) excluded.insert(std::upper_bound(excluded.begin(), excluded.end(), p), p);
    out.pins.insert(out.pins.end(), pins.begin(), pins.end());
  }
  std::sort(out.pins.begin(), out.pins.end());
  return out;
}

}  // namespace perimorph::evolution
