#include "perimorph/evolution/checkpoint.hpp"

#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/evolution/adaptivity.hpp"
#include "perimorph/evolution/local_damage.hpp"
#include "perimorph/evolution/part_support.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

namespace perimorph::evolution {

namespace {

void put_vec3(core::BinaryWriter& out, const Vec3& v) {
  for (int k = 0; k < 3; ++k) out.put<double>(v[k]);
}
Vec3 get_vec3(core::BinaryReader& in) {
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = in.get<double>();
  return v;
}

template <class T>
void check_size(core::BinaryReader& in, const std::vector<T>& v, std::size_t expected, const char* what) {
  if (v.size() != expected)
    in.fail(fmt::format("{} of {} values where the model has {}", what, v.size(), expected));
}

void save_ball(core::BinaryWriter& out, const AlphaBall& b) {
  out.put<int>(b.increment);
  out.put<Index>(b.cell);
  put_vec3(out, b.center);
  out.put<double>(b.radius);
  out.put<double>(b.transition);
  out.put<char>(b.predicted);
  out.put<char>(b.critical_damage);
}

AlphaBall restore_ball(core::BinaryReader& in) {
  AlphaBall b;
  b.increment = in.get<int>();
  b.cell = in.get<Index>();
  b.center = get_vec3(in);
  b.radius = in.get<double>();
  b.transition = in.get<double>();
  b.predicted = in.get<char>() != 0;
  b.critical_damage = in.get<char>() != 0;
  return b;
}

void save_balls(core::BinaryWriter& out, const std::vector<AlphaBall>& balls) {
  out.put<std::uint64_t>(balls.size());
  for (const auto& b : balls) save_ball(out, b);
}

std::vector<AlphaBall> restore_balls(core::BinaryReader& in) {
  const auto n = in.get<std::uint64_t>();
  std::vector<AlphaBall> balls;
  for (std::uint64_t k = 0; k < n; ++k) balls.push_back(restore_ball(in));
  return balls;
}

}  // namespace

void save_alpha(const alpha::AlphaField& alpha, core::BinaryWriter& out) {
  out.tag("alpha");
  out.put<double>(alpha.constant_value());
  out.put<int>(alpha.dim());
  out.put<std::uint64_t>(alpha.region_list().size());
  for (const alpha::Region& r : alpha.region_list()) {
    out.put<double>(r.transition);
    out.put<int>(static_cast<int>(r.profile));
    out.put<int>(static_cast<int>(r.shape.index()));
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, alpha::Interval>) {
            out.put<double>(s.lower);
            out.put<double>(s.upper);
          } else if constexpr (std::is_same_v<S, alpha::Slab>) {
            put_vec3(out, s.point);
            put_vec3(out, s.normal);
            out.put<double>(s.half_width);
          } else if constexpr (std::is_same_v<S, alpha::Ball>) {
            put_vec3(out, s.center);
            out.put<double>(s.radius);
          } else if constexpr (std::is_same_v<S, alpha::Cylinder>) {
            put_vec3(out, s.point);
            put_vec3(out, s.axis);
            out.put<double>(s.radius);
          } else {
            put_vec3(out, s.lower);
            put_vec3(out, s.upper);
          }
        },
        r.shape);
  }
}

alpha::AlphaField restore_alpha(core::BinaryReader& in) {
  in.expect("alpha");
  const double constant = in.get<double>();
  const int dim = in.get<int>();
  const auto n = in.get<std::uint64_t>();
  std::vector<alpha::Region> regions;
  for (std::uint64_t k = 0; k < n; ++k) {
    alpha::Region r;
    r.transition = in.get<double>();
    const int profile = in.get<int>();
    if (profile < 0 || profile > static_cast<int>(alpha::Profile::cubic)) in.fail("an unknown α profile");
    r.profile = static_cast<alpha::Profile>(profile);
    switch (in.get<int>()) {
      case 0: {
        alpha::Interval s;
        s.lower = in.get<double>();
        s.upper = in.get<double>();
        r.shape = s;
        break;
      }
      case 1: {
        alpha::Slab s;
        s.point = get_vec3(in);
        s.normal = get_vec3(in);
        s.half_width = in.get<double>();
        r.shape = s;
        break;
      }
      case 2: {
        alpha::Ball s;
        s.center = get_vec3(in);
        s.radius = in.get<double>();
        r.shape = s;
        break;
      }
      case 3: {
        alpha::Cylinder s;
        s.point = get_vec3(in);
        s.axis = get_vec3(in);
        s.radius = in.get<double>();
        r.shape = s;
        break;
      }
      case 4: {
        alpha::Box s;
        s.lower = get_vec3(in);
        s.upper = get_vec3(in);
        r.shape = s;
        break;
      }
      default:
        in.fail("an unknown α shape");
    }
    regions.push_back(r);
  }
  return alpha::AlphaField::exactly(constant, dim, std::move(regions));
}

void save_state(const RunState& state, core::BinaryWriter& out) {
  out.tag("state");
  out.put<int>(state.increment);
  out.put<double>(state.load_factor);
  out.put_vector(state.u);
  save_alpha(state.alpha, out);
  std::vector<Index> failed;
  std::vector<int> points;
  for (const auto& b : state.failed_in_order) {
    failed.insert(failed.end(), {b.e, b.f});
    points.insert(points.end(), {b.g, b.h});
  }
  out.put_vector(failed);
  out.put_vector(points);
  std::vector<double> cell_dissipated(static_cast<std::size_t>(state.num_cells), 0.0);
  for (const auto& [c, d] : state.cell_dissipated) cell_dissipated[static_cast<std::size_t>(c)] = d;
  out.put_vector(cell_dissipated);
  out.put_vector(state.held_dofs);
  out.put<std::uint64_t>(state.detached_dofs);
  out.put<std::uint64_t>(state.floating_parts);
  out.put<std::uint64_t>(state.cell_mechanisms);
  out.put_vector(state.history);
  const EnergyLedger& e = state.energy;
  for (double v :
       {e.external_work, e.strain_energy, e.dissipated, e.overshoot, e.damage_dissipated, e.model_change})
    out.put<double>(v);
}

void restore_state(RunState& state, core::BinaryReader& in) {
  in.expect("state");
  state.increment = in.get<int>();
  state.load_factor = in.get<double>();
  std::vector<double> u = in.get_vector<double>();
  check_size(in, u, state.u.size(), "a displacement");
  state.u = std::move(u);
  state.alpha = restore_alpha(in);
  const auto failed = in.get_vector<Index>();
  const auto points = in.get_vector<int>();
  if (failed.size() != points.size()) in.fail("failed bonds that do not add up");
  state.failed_in_order.clear();
  for (std::size_t k = 0; k + 1 < failed.size(); k += 2) {
    const bonds::BondId id{failed[k], failed[k + 1], points[k], points[k + 1]};
    if (!state.failed.valid(id)) in.fail("a failed bond outside the model");
    state.failed.add(id);
    state.failed_in_order.push_back(id);
  }
  state.failed_over_model = state.failed_in_order.size();
  state.failed_place.clear();
  const std::vector<double> cell_dissipated = in.get_vector<double>();
  check_size(in, cell_dissipated, static_cast<std::size_t>(state.num_cells), "a dissipation per cell");
  state.cell_dissipated.clear();
  for (std::size_t c = 0; c < cell_dissipated.size(); ++c)
    if (cell_dissipated[c] != 0.0) state.cell_dissipated[static_cast<Index>(c)] = cell_dissipated[c];
  state.held_dofs = in.get_vector<Index>();
  for (Index d : state.held_dofs)
    if (d < 0 || static_cast<std::size_t>(d) >= state.u.size()) in.fail("a held dof out of range");
  state.detached_dofs = in.get<std::uint64_t>();
  state.floating_parts = in.get<std::uint64_t>();
  state.cell_mechanisms = in.get<std::uint64_t>();
  std::vector<double> history = in.get_vector<double>();
  check_size(in, history, state.history.size(), "a damage history");
  state.history = std::move(history);
  EnergyLedger& e = state.energy;
  for (double* v : {&e.external_work, &e.strain_energy, &e.dissipated, &e.overshoot, &e.damage_dissipated,
                    &e.model_change})
    *v = in.get<double>();
}

void Adaptivity::save(core::BinaryWriter& out) const {
  out.tag("adaptivity");
  out.put<char>(growth_due_);
  out.put<std::uint64_t>(seen_);
  out.put<std::uint64_t>(checked_);
  save_balls(out, silent_);
  save_balls(out, balls_);
}

void Adaptivity::restore(const setup::Discretization& disc, core::BinaryReader& in) {
  in.expect("adaptivity");
  disc_ = &disc;
  growth_due_ = in.get<char>() != 0;
  seen_ = in.get<std::uint64_t>();
  checked_ = in.get<std::uint64_t>();
  silent_ = restore_balls(in);
  balls_ = restore_balls(in);
  proposed_.clear();
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());
  seeded_.clear();
  for (const auto* balls : {&silent_, &balls_})
    for (const AlphaBall& b : *balls) seeded_.insert(b.cell);
}

void PartSupport::save(core::BinaryWriter& out) const {
  // A checkpoint is written when the increment has settled (every component
  // proposed nothing), so the last inspect's lists are empty: nothing to
  // renumber on a piece of the model, whose lists are of dof names.
  PERIMORPH_ASSERT(!disc_->piece || (detached_.empty() && pins_.empty() && cell_pins_.empty()),
                   "a checkpoint of a run on pieces of the model with dofs about to be held");
  out.tag("part support");
  out.put<std::uint64_t>(seen_);
  out.put<std::uint64_t>(downdates_seen_);
  out.put_vector(detached_);
  out.put_vector(pins_);
  out.put_vector(cell_pins_);
  out.put<int>(parts_);
  out.put<std::uint64_t>(mechanisms_);
}

void PartSupport::restore(const setup::Discretization& disc, core::BinaryReader& in) {
  in.expect("part support");
  disc_ = &disc;
  seen_ = in.get<std::uint64_t>();
  downdates_seen_ = in.get<std::uint64_t>();
  detached_ = in.get_vector<Index>();
  pins_ = in.get_vector<Index>();
  cell_pins_ = in.get_vector<Index>();
  parts_ = in.get<int>();
  mechanisms_ = in.get<std::uint64_t>();
}

void LocalDamage::save(core::BinaryWriter& out) const {
  out.tag("local damage");
  out.put<int>(newton_steps_);
  out.put<int>(newton_failures_);
  out.put<int>(newton_failed_in_);
  out.put<double>(largest_);
}

void LocalDamage::restore(const setup::Discretization& disc, core::BinaryReader& in) {
  in.expect("local damage");
  disc_ = &disc;
  decides_ = setup::cells_of_process(disc, la::world_size(), la::world_rank());
  holders_ = CellHolders(disc, decides_);
  newton_steps_ = in.get<int>();
  newton_failures_ = in.get<int>();
  newton_failed_in_ = in.get<int>();
  largest_ = in.get<double>();
  proposed_ = {};
}

}  // namespace perimorph::evolution
