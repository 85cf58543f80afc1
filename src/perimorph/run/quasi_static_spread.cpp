// Where a quasi-static run's vectors live when it is spread over processes
// (issue 17): u at the process's halo, K u and the last recorded state at
// its owned dofs, and the sums over them. Part of QuasiStaticRun
// (quasi_static_run.hpp).

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/run/quasi_static_run.hpp"
#include "perimorph/setup/discretization.hpp"

#include <limits>

namespace perimorph::run {

void QuasiStaticRun::choose_gather() {
  halo_.reset();
  const auto* d = u_.distribution();
  owned_dofs_ = system_->owned_dofs();  // the system's arrays at the owned dofs are in its order
  PERIMORPH_ASSERT(owned_dofs_.size() == (d ? static_cast<std::size_t>(d->owned_nodes() * disc_->dim())
                                            : static_cast<std::size_t>(disc_->dofmap.num_dofs())),
                   "the run's vectors are laid out as the system's");
  if (!d) return;
  std::vector<Index> nodes = setup::nodes_read(*disc_);
  std::vector<char> read(static_cast<std::size_t>(d->num_nodes()), 0);
  for (Index n : nodes) read[static_cast<std::size_t>(n)] = 1;
  for (Index n = 0; n < d->num_nodes(); ++n)
    PERIMORPH_ASSERT(!d->owns(n) || read[static_cast<std::size_t>(n)],
                     "a process must read the dofs it owns");
  halo_.emplace(u_.shared_distribution(), disc_->dim(), std::move(nodes));
}

std::vector<double> QuasiStaticRun::gather(const la::Vector& v) {
  if (!halo_) return v.to_std();
  return halo_->gathered(v, std::numeric_limits<double>::quiet_NaN());
}

std::vector<double> QuasiStaticRun::owned(const la::Vector& v) const {
  return v.at_owned(owned_dofs_);
}

std::vector<double> QuasiStaticRun::whole(const std::vector<double>& v) const {
  if (!halo_) return v;
  PERIMORPH_ASSERT(!disc_->piece, "a run on pieces of the model holds no whole vector");
  la::Vector x = system_->make_vector();
  x.assign_replicated(v);
  return x.to_replicated();
}

std::size_t QuasiStaticRun::bonds_failed() const {
  return state_.failed_over_model;
}

double QuasiStaticRun::add_over_dofs(double init, const std::function<double(std::size_t)>& term) const {
  return owned_dofs_.sum(init, term);
}

std::vector<Vec3> QuasiStaticRun::reactions(std::span<const double> r) const {
  const int dim = disc_->dim();
  std::vector<Vec3> out;
  for (const auto& s : setup_.sets) {
    Vec3 f = Vec3::Zero();
    for (Index n : s.dof_nodes) {
      const std::ptrdiff_t at = owned_dofs_.position(n * dim);
      if (at < 0) continue;
      for (int d = 0; d < dim; ++d) f[d] += r[static_cast<std::size_t>(at + d)];
    }
    out.push_back(f);
  }
  if (!halo_) return out;
  std::vector<double> flat;
  for (const Vec3& f : out) flat.insert(flat.end(), f.data(), f.data() + 3);
  flat = la::sum_over_processes(std::move(flat));
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = Vec3(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return out;
}

}  // namespace perimorph::run
