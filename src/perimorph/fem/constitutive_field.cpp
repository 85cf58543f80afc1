#include "perimorph/fem/constitutive_field.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/fem/material.hpp"

namespace perimorph::fem {

ConstitutiveField::ConstitutiveField(int dim, Index num_cells, int points_per_cell)
    : dim_(dim),
      nv_(voigt_size(dim)),
      npts_(points_per_cell),
      first_(static_cast<std::size_t>(num_cells), -1),
      per_point_(static_cast<std::size_t>(num_cells), 0) {}

int ConstitutiveField::add_tensor(const Eigen::MatrixXd& C) {
  PERIMORPH_ASSERT(C.rows() == nv_ && C.cols() == nv_, "tensor size does not match the model dimension");
  const auto id = static_cast<int>(data_.size() / static_cast<std::size_t>(nv_ * nv_));
  data_.insert(data_.end(), C.data(), C.data() + nv_ * nv_);
  return id;
}

void ConstitutiveField::set_cell(Index c, int id) {
  first_[static_cast<std::size_t>(c)] = id;
  per_point_[static_cast<std::size_t>(c)] = 0;
}

void ConstitutiveField::set_cell_points(Index c, std::span<const Eigen::MatrixXd> C) {
  PERIMORPH_ASSERT(static_cast<int>(C.size()) == npts_, "one tensor per quadrature point expected");
  const int id = add_tensor(C[0]);
  for (std::size_t q = 1; q < C.size(); ++q) add_tensor(C[q]);
  first_[static_cast<std::size_t>(c)] = id;
  per_point_[static_cast<std::size_t>(c)] = 1;
}

ConstitutiveField ConstitutiveField::cells_of(std::span<const Index> cells) const {
  ConstitutiveField out(dim_, static_cast<Index>(cells.size()), npts_);
  const auto n = static_cast<std::size_t>(nv_ * nv_);
  std::vector<Index> moved(data_.size() / n, -1);  // each tensor's id in `out`, once copied
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const Index c = cells[k];
    PERIMORPH_ASSERT(c >= 0 && c < num_cells(), "cells_of: a cell of the field");
    const Index first = first_[static_cast<std::size_t>(c)];
    const bool per_point = per_point_[static_cast<std::size_t>(c)] != 0;
    out.per_point_[k] = per_point_[static_cast<std::size_t>(c)];
    if (first < 0) continue;  // no tensor set
    if (moved[static_cast<std::size_t>(first)] < 0) {
      moved[static_cast<std::size_t>(first)] = static_cast<Index>(out.data_.size() / n);
      const std::size_t count = per_point ? static_cast<std::size_t>(npts_) : 1;
      const auto* begin = data_.data() + static_cast<std::size_t>(first) * n;
      out.data_.insert(out.data_.end(), begin, begin + count * n);
    }
    out.first_[k] = moved[static_cast<std::size_t>(first)];
  }
  return out;
}

void ConstitutiveField::add_to_all(const Eigen::MatrixXd& T) {
  PERIMORPH_ASSERT(T.rows() == nv_ && T.cols() == nv_, "tensor size does not match the model dimension");
  const auto n = static_cast<std::size_t>(nv_ * nv_);
  for (std::size_t k = 0; k < data_.size(); ++k) data_[k] += T.data()[k % n];
}

}  // namespace perimorph::fem
