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
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());
}

bool Adaptivity::decides(Index c) const {
  return decides_.empty() || decides_[static_cast<std::size_t>(c)] != 0;
}

bool Adaptivity::seeded(Index c) const {
  return seeded_.contains(setup::global_cell(*disc_, c));
}

void Adaptivity::candidate(std::vector<Candidate>& out, int phase, double order, Index c, int increment,
                           bool predicted, bool critical_damage) const {
  const mesh::Mesh& m = disc_->mesh;
  out.push_back({phase,
                 order,
                 {increment, setup::global_cell(*disc_, c), m.cell_centroid(c), cell_size(m, c) + core_,
                  transition_, predicted, critical_damage}});
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
    if (!decides(c)) continue;
    const double reach = b.radius + b.transition + cell_size(m, c);
    if (distance(m.cell_centroid(c), b.center, dim) > reach) continue;
    PERIMORPH_ASSERT(pts.holds(c), "the non-local points of a cell this process decides on");
    std::copy_n(pts.x.begin() + static_cast<std::ptrdiff_t>(pts.index(c, 0)), xp.size(), xp.begin());
    std::copy_n(pts.alpha.begin() + static_cast<std::ptrdiff_t>(pts.index(c, 0)), ap.size(), ap.begin());
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

void Adaptivity::check_predictor_in_time(const RunState& state) {
  // Every process holding a failed bond sees the same α at its cells; the
  // first late one, by its place in the order of failure, names the cell.
  const auto& points = disc_->nonlocal->points;
  const auto& failed = state.failed_in_order;
  std::vector<double> late;
  for (std::size_t k = state.failed_after(checked_); k < failed.size() && late.empty(); ++k)
    for (Index c : {failed[k].e, failed[k].f})
      if (points.cell_alpha_min[static_cast<std::size_t>(c)] < 1.0 && late.empty()) {
        const Vec3 x = disc_->mesh.cell_centroid(c);
        const std::size_t place = state.failed_place.empty() ? k : state.failed_place[k];
        late = {static_cast<double>(place), static_cast<double>(setup::global_cell(*disc_, c)), x.x(), x.y(),
                x.z()};
      }
  checked_ = state.failed_over_model;
  if (disc_->piece) late = la::all_gather(late);  // elsewhere every process holds every failed bond
  if (late.empty()) return;
  std::size_t first = 0;
  for (std::size_t k = 5; k < late.size(); k += 5)
    if (late[k] < late[first]) first = k;
  const auto& spec = disc_->config.adaptivity;
  throw Error(fmt::format(
      "a bond failed in cell {} (centroid {:.4g}, {:.4g}, {:.4g}), where α < 1: the predictor was "
      "late (the bond reached s_crit before the strain of a cell with α < 1 reached theta · s_crit = "
      "{:g}). Lower [adaptivity] theta (now {}) or the load increments",
      static_cast<Index>(late[first + 1]), late[first + 2], late[first + 3], late[first + 4],
      spec.theta * s_crit_, spec.theta));
}

Proposal Adaptivity::inspect(const RunState& state, const system::ConstrainedSystem& /*system*/) {
  // Proposed cells are marked seeded at once; a proposal not applied is
  // impossible (the run applies every non-quiet proposal). Each process
  // finds the candidates among the cells it decides on (u and d are exact
  // there), ordered as one process finds them: predictor hits, then critical
  // damage, both in cell order, then the cells of the failed bonds in their
  // order of failure; gathered, every process proposes the same balls.
  proposed_.clear();
  const auto& spec = disc_->config.adaptivity;
  const auto& points = disc_->nonlocal->points;
  std::vector<Candidate> mine;
  const auto cells = disc_->mesh.num_cells();
  if (spec.predictor) {
    check_predictor_in_time(state);
    const double bar = spec.theta * s_crit_;
    const assembly::LocalSpace space = disc_->local_space();
    for (Index c = 0; c < cells; ++c) {
      if (!decides(c) || seeded(c) || points.cell_alpha_min[static_cast<std::size_t>(c)] >= 1.0) continue;
      for (const auto& q : disc_->rule)
        if (largest_principal_strain(assembly::strain_at(space, c, q.xi, state.u), disc_->dim()) > bar) {
          candidate(mine, 0, static_cast<double>(setup::global_cell(*disc_, c)), c, state.increment, true);
          break;
        }
    }
  }
  // allow_growth() opens one inspect: growth from failed bonds is due once.
  const bool grow = spec.update == casefile::AdaptivityUpdate::iteration || growth_due_;
  growth_due_ = false;
  if (grow) {
    if (disc_->damage) {
      const setup::DamageModel& dm = *disc_->damage;
      const int npts = dm.points_per_cell;
      for (Index c = 0; c < cells; ++c) {
        const int law = dm.law_of(c);
        if (law < 0 || !decides(c) || seeded(c)) continue;
        const double d_c = dm.laws[static_cast<std::size_t>(law)].d_c;
        for (int q = 0; q < npts; ++q)
          if (setup::DamageModel::at(state.history, c, q, npts) >= d_c) {
            candidate(mine, 1, static_cast<double>(setup::global_cell(*disc_, c)), c, state.increment, false,
                      true);
            break;
          }
      }
    }
    // The bonds' places are below 2^53 / 2: exact as doubles.
    const auto& failed = state.failed_in_order;
    for (std::size_t k = state.failed_after(seen_); k < failed.size(); ++k) {
      const double place = static_cast<double>(state.failed_place.empty() ? k : state.failed_place[k]);
      for (int end = 0; end < 2; ++end)
        if (const Index c = end == 0 ? failed[k].e : failed[k].f; decides(c) && !seeded(c))
          candidate(mine, 2, 2.0 * place + end, c, state.increment, false);
    }
    seen_ = state.failed_over_model;
  }
  for (const Candidate& k : gathered(std::move(mine), state.increment))
    if (seeded_.insert(k.ball.cell).second) proposed_.push_back(k.ball);
  // A ball that raises α at no quadrature point leaves the discretization as
  // it is: it joins α without a rebuild (join_silent).
  std::vector<char> raises(proposed_.size());
  for (std::size_t k = 0; k < proposed_.size(); ++k) raises[k] = raises_alpha(proposed_[k]) ? 1 : 0;
  if (!decides_.empty()) raises = la::union_over_processes(std::move(raises));
  std::vector<AlphaBall> raising;
  for (std::size_t k = 0; k < proposed_.size(); ++k) (raises[k] ? raising : silent_).push_back(proposed_[k]);
  proposed_ = std::move(raising);
  return {proposed_.size()};
}

std::vector<Adaptivity::Candidate> Adaptivity::gathered(std::vector<Candidate> mine, int increment) const {
  if (!decides_.empty()) {  // spread over processes: every process's, in the order of one
    std::vector<double> flat;
    for (const Candidate& k : mine) {
      const AlphaBall& b = k.ball;
      flat.insert(flat.end(), {static_cast<double>(k.phase), k.order, static_cast<double>(b.cell),
                               b.center.x(), b.center.y(), b.center.z(), b.radius, b.predicted ? 1.0 : 0.0,
                               b.critical_damage ? 1.0 : 0.0});
    }
    flat = la::all_gather(flat);
    mine.clear();
    for (std::size_t k = 0; k + 9 <= flat.size(); k += 9)
      mine.push_back(
          {static_cast<int>(flat[k]),
           flat[k + 1],
           {increment, static_cast<Index>(flat[k + 2]), Vec3(flat[k + 3], flat[k + 4], flat[k + 5]),
            flat[k + 6], transition_, flat[k + 7] != 0.0, flat[k + 8] != 0.0}});
  }
  std::stable_sort(mine.begin(), mine.end(), [](const Candidate& a, const Candidate& b) {
    return a.phase != b.phase ? a.phase < b.phase : a.order < b.order;
  });
  return mine;
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
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());  // a new piece: new cells
}

}  // namespace perimorph::evolution
