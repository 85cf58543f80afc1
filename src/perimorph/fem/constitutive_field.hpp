#pragma once
// The local stiffness C(x) at every quadrature point of every cell, in the
// model's Voigt form (1×1, 3×3 or 6×6). The morphing method varies C point by
// point (THEORY §3, eq. 2.28), so storage is per point where needed and per
// cell where C is uniform over the cell (the common case, kept compact).

#include "perimorph/core/types.hpp"

#include <Eigen/Core>

#include <cassert>
#include <span>
#include <vector>

namespace perimorph::fem {

class ConstitutiveField {
 public:
  ConstitutiveField(int dim, Index num_cells, int points_per_cell);

  int dim() const { return dim_; }
  int voigt() const { return nv_; }
  int points_per_cell() const { return npts_; }
  Index num_cells() const { return static_cast<Index>(first_.size()); }

  /// Stores a tensor and returns its id (for set_cell).
  int add_tensor(const Eigen::MatrixXd& C);
  /// Cell c uses tensor `id` at every point.
  void set_cell(Index c, int id);
  /// Cell c uses one tensor per point (points_per_cell of them, in order).
  void set_cell_points(Index c, std::span<const Eigen::MatrixXd> C);

  /// The field of the listed cells (each a cell of this field): cell k of the
  /// result is cells[k], its tensors copied (the same bits), a tensor shared
  /// by several listed cells shared again. A process's piece of a model
  /// (setup::cut_to_piece).
  ConstitutiveField cells_of(std::span<const Index> cells) const;

  /// Adds T to every stored tensor, so to C at every point of every cell.
  void add_to_all(const Eigen::MatrixXd& T);

  /// Column-major nv × nv tensor at point q of cell c.
  const double* at(Index c, int q) const {
    assert(c >= 0 && c < num_cells() && q >= 0 && q < npts_);
    const auto k = static_cast<std::size_t>(first_[static_cast<std::size_t>(c)] +
                                            (per_point_[static_cast<std::size_t>(c)] ? q : 0));
    return data_.data() + k * static_cast<std::size_t>(nv_ * nv_);
  }
  Eigen::Map<const Eigen::MatrixXd> matrix(Index c, int q) const { return {at(c, q), nv_, nv_}; }
  /// The bytes its arrays hold (tensors and the per-cell index).
  std::size_t bytes() const {
    return data_.size() * sizeof(double) + first_.size() * sizeof(Index) + per_point_.size();
  }

 private:
  int dim_, nv_, npts_;
  std::vector<double> data_;
  std::vector<Index> first_;
  std::vector<std::uint8_t> per_point_;
};

}  // namespace perimorph::fem
