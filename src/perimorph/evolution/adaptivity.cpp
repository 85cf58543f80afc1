#include "perimorph/evolution/adaptivity.hpp"

#include "perimorph/assembly/local_assembly.hpp"
#include "perimorph/assembly/morphed_stiffness.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace perimorph::evolution {

namespace {

/// The largest principal value of a Voigt strain (engineering shear) of the
/// model dimension: the largest stretch of any direction (THEORY §5, s = n·ε·n).
double largest_principal_strain(std::span<const double> voigt, int dim) {
  if (dim == 1) return voigt[0];
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  if (dim == 2) {
    e(0, 0) = voigt[0];
    e(1, 1) = voigt[1];
    e(0, 1) = e(1, 0) = 0.5 * voigt[2];
  } else {  // xx yy zz yz xz xy
    e(0, 0) = voigt[0];
    e(1, 1) = voigt[1];
    e(2, 2) = voigt[2];
    e(1, 2) = e(2, 1) = 0.5 * voigt[3];
    e(0, 2) = e(2, 0) = 0.5 * voigt[4];
    e(0, 1) = e(1, 0) = 0.5 * voigt[5];
  }
  const int n = dim;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(e.topLeftCorner(n, n), Eigen::EigenvaluesOnly);
  return solver.eigenvalues().maxCoeff();
}

/// |x − y| in the first dim coordinates.
double distance(const Vec3& x, const Vec3& y, int dim) {
  double d2 = 0.0;
  for (int d = 0; d < dim; ++d) d2 += (x[d] - y[d]) * (x[d] - y[d]);
  return std::sqrt(d2);
}

/// The longest side of the cell's bounding box: h_e of THEORY §5.
double cell_size(const mesh::Mesh& m, Index c) {
  double size = 0.0;
  for (int d = 0; d < m.dim(); ++d) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (Index n : m.cell(c)) {
      lo = std::min(lo, m.node(n)[d]);
      hi = std::max(hi, m.node(n)[d]);
    }
    size = std::max(size, hi - lo);
  }
  return size;
}

}  // namespace

Adaptivity::Adaptivity(const setup::Discretization& disc, double s_crit) : disc_(&disc), s_crit_(s_crit) {
  const auto& spec = disc.config.adaptivity;
  const double delta = disc.config.nonlocal.horizon;
  core_ = spec.core >= 0.0 ? spec.core : delta;
  transition_ = spec.transition >= 0.0 ? spec.transition : delta;
  seeded_.assign(static_cast<std::size_t>(disc.mesh.num_cells()), 0);
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());
}

void Adaptivity::propose(Index cell, int increment, bool predicted, bool critical_damage) {
  char& seeded = seeded_[static_cast<std::size_t>(cell)];
  if (seeded) return;
  seeded = 1;
  const mesh::Mesh& m = disc_->mesh;
  proposed_.push_back({increment, cell, m.cell_centroid(cell), cell_size(m, cell) + core_, transition_,
                       predicted, critical_damage});
}

bool Adaptivity::raises_alpha(const AlphaBall& b) const {
  const mesh::Mesh& m = disc_->mesh;
  const auto& nl = *disc_->nonlocal;
  const alpha::Region ball{alpha::Ball{b.center, b.radius}, b.transition,
                           setup::alpha_profile(disc_->config.adaptivity.profile)};
  const int dim = m.dim();
  const std::size_t nq = disc_->rule.size();
  const auto& pts = nl.points;
  std::vector<Vec3> xp(static_cast<std::size_t>(pts.per_cell));
  std::vector<double> ap(xp.size());
  for (Index c = 0; c < m.num_cells(); ++c) {
    const double reach = b.radius + b.transition + cell_size(m, c);
    if (distance(m.cell_centroid(c), b.center, dim) > reach) continue;
    if (pts.holds(c)) {  // else (a process of a distributed run) recomputed: the same values
      std::copy_n(pts.x.begin() + static_cast<std::ptrdiff_t>(pts.index(c, 0)), xp.size(), xp.begin());
      std::copy_n(pts.alpha.begin() + static_cast<std::ptrdiff_t>(pts.index(c, 0)), ap.size(), ap.begin());
    } else {
      bonds::compute_cell_points(m, c, pts.rule, {}, pts.scale, nl.alpha, xp.data(), nullptr, ap.data(),
                                 nullptr);
    }
    for (std::size_t q = 0; q < xp.size(); ++q)
      if (alpha::region_value(ball, xp[q], dim) > ap[q]) return true;
    for (std::size_t q = 0; q < nq; ++q) {
      const Vec3 x = assembly::physical_point(m, c, disc_->rule[q].xi);
      if (alpha::region_value(ball, x, dim) >
          assembly::alpha_at_local_point(m, nl.alpha, c, disc_->rule[q].xi))
        return true;
    }
  }
  return false;
}

Proposal Adaptivity::inspect(const RunState& state, const system::ConstrainedSystem& /*system*/) {
  // Proposed cells are marked seeded at once; a proposal not applied is
  // impossible (the run applies every non-quiet proposal).
  proposed_.clear();
  const auto& spec = disc_->config.adaptivity;
  const auto& points = disc_->nonlocal->points;
  const auto& failed = state.failed_in_order;
  if (spec.predictor) {
    for (; checked_ < failed.size(); ++checked_) {
      const auto& id = failed[checked_];
      for (Index c : {id.e, id.f})
        if (points.cell_alpha_min[static_cast<std::size_t>(c)] < 1.0) {
          const Vec3 x = disc_->mesh.cell_centroid(c);
          throw Error(fmt::format(
              "a bond failed in cell {} (centroid {:.4g}, {:.4g}, {:.4g}), where α < 1: the predictor was "
              "late (the bond reached s_crit before the strain of a cell with α < 1 reached theta · s_crit = "
              "{:g}). Lower [adaptivity] theta (now {}) or the load increments",
              c, x.x(), x.y(), x.z(), spec.theta * s_crit_, spec.theta));
        }
    }
    const double bar = spec.theta * s_crit_;
    const assembly::LocalSpace space = disc_->local_space();
    // Each process tests the cells of its part (u is exact there); the hits,
    // gathered and put in cell order, are proposed as on one process.
    std::vector<double> hits;
    for (Index c = 0; c < disc_->mesh.num_cells(); ++c) {
      if (seeded_[static_cast<std::size_t>(c)] || points.cell_alpha_min[static_cast<std::size_t>(c)] >= 1.0 ||
          (!decides_.empty() && decides_[static_cast<std::size_t>(c)] == 0))
        continue;
      for (const auto& q : disc_->rule)
        if (largest_principal_strain(assembly::strain_at(space, c, q.xi, state.u), disc_->dim()) > bar) {
          hits.push_back(static_cast<double>(c));
          break;
        }
    }
    if (!decides_.empty()) {
      hits = la::all_gather(hits);
      std::sort(hits.begin(), hits.end());
    }
    for (double c : hits) propose(static_cast<Index>(c), state.increment, true);
  }
  // allow_growth() opens one inspect: growth from failed bonds is due once.
  const bool grow = spec.update == casefile::AdaptivityUpdate::iteration || growth_due_;
  growth_due_ = false;
  if (grow) {
    if (disc_->damage) {
      const setup::DamageModel& dm = *disc_->damage;
      const int npts = dm.points_per_cell;
      for (Index c = 0; c < disc_->mesh.num_cells(); ++c) {
        const int law = dm.law_of(c);
        if (law < 0 || seeded_[static_cast<std::size_t>(c)]) continue;
        const double d_c = dm.laws[static_cast<std::size_t>(law)].d_c;
        for (int q = 0; q < npts; ++q)
          if (setup::DamageModel::at(state.history, c, q, npts) >= d_c) {
            propose(c, state.increment, false, true);
            break;
          }
      }
    }
    for (; seen_ < failed.size(); ++seen_)
      for (Index c : {failed[seen_].e, failed[seen_].f}) propose(c, state.increment, false);
  }
  // A ball that raises α at no quadrature point leaves the discretization as
  // it is: it joins α without a rebuild (join_silent).
  std::erase_if(proposed_, [&](const AlphaBall& b) {
    if (raises_alpha(b)) return false;
    silent_.push_back(b);
    return true;
  });
  return {proposed_.size()};
}

void Adaptivity::join(std::vector<AlphaBall>& balls, RunState& state) {
  std::vector<alpha::Region> regions;
  const alpha::Profile profile = setup::alpha_profile(disc_->config.adaptivity.profile);
  for (const AlphaBall& b : balls)
    regions.push_back({alpha::Ball{b.center, b.radius}, b.transition, profile});
  state.alpha = state.alpha.grown(std::move(regions), disc_->dim());
  balls_.insert(balls_.end(), balls.begin(), balls.end());
  balls.clear();
}

Effect Adaptivity::apply(RunState& state, system::ConstrainedSystem& /*system*/) {
  join(silent_, state);
  join(proposed_, state);
  return Effect::rebuild;
}

void Adaptivity::join_silent(RunState& state) {
  join(silent_, state);
}

void Adaptivity::rebind(const setup::Discretization& disc, RunState& /*state*/,
                        system::ConstrainedSystem& /*system*/) {
  disc_ = &disc;
}

}  // namespace perimorph::evolution
