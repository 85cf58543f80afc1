#include "perimorph/evolution/bond_decisions.hpp"

#include "perimorph/bonds/nonlocal_points.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <numeric>

namespace perimorph::evolution {

CellHolders::CellHolders(const setup::Discretization& disc, std::span<const char> decides) {
  if (decides.empty()) return;  // one process
  const int processes = la::world_size(), rank = la::world_rank();
  if (!disc.piece) {
    every_process_ = true;
    for (int p = 0; p < processes; ++p)
      if (p != rank) others_.push_back(p);
    return;
  }
  // Each process tells the deciding process of every cell it holds and does not decide.
  const auto& numbers = *disc.piece;
  std::vector<la::Parcel> out;
  for (Index c = 0; c < disc.mesh.num_cells(); ++c) {
    if (numbers.of_part(c)) continue;
    const int owner = numbers.owner[static_cast<std::size_t>(c)];
    la::parcel_for(out, owner).push_back(static_cast<double>(setup::global_cell(disc, c)));
  }
  const std::vector<la::Parcel> in = la::exchange(out);
  const auto cells = static_cast<std::size_t>(disc.mesh.num_cells());
  offsets_.assign(cells + 1, 0);
  std::vector<Index> local;  // per received value, its local cell
  for (const la::Parcel& p : in)
    for (double v : p.values) {
      const Index c = setup::local_cell(disc, static_cast<Index>(v));
      PERIMORPH_ASSERT(c >= 0 && numbers.of_part(c), "a process holds a cell this one does not decide");
      local.push_back(c);
      ++offsets_[static_cast<std::size_t>(c) + 1];
    }
  std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
  ranks_.assign(local.size(), 0);
  std::vector<Index> fill(offsets_.begin(), offsets_.end() - 1);
  std::size_t k = 0;
  for (const la::Parcel& p : in)  // by sender: each cell's processes ascending
    for (std::size_t j = 0; j < p.values.size(); ++j, ++k)
      ranks_[static_cast<std::size_t>(fill[static_cast<std::size_t>(local[k])]++)] = p.process;
}

std::span<const int> CellHolders::of(Index c) const {
  if (every_process_) return others_;
  if (offsets_.empty()) return {};
  const auto i = static_cast<std::size_t>(c);
  return {ranks_.data() + offsets_[i], static_cast<std::size_t>(offsets_[i + 1] - offsets_[i])};
}

namespace {

constexpr std::size_t kBond = 10;     ///< doubles a bond sent to a holder
constexpr std::size_t kSummary = 5;   ///< doubles a cell in the pass's summary
constexpr std::size_t kWritten = 16;  ///< doubles a bond gathered for process 0

void pack_bond(const assembly::StretchedBond& b, Index e, Index f, std::vector<double>& out) {
  out.insert(out.end(),
             {static_cast<double>(e), static_cast<double>(f), static_cast<double>(b.id.g),
              static_cast<double>(b.id.h), b.stretch, b.energy, b.k, b.xi.x(), b.xi.y(), b.xi.z()});
}

assembly::StretchedBond unpack_bond(const double* v) {
  assembly::StretchedBond b;
  b.id = {static_cast<Index>(v[0]), static_cast<Index>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3])};
  b.stretch = v[4];
  b.energy = v[5];
  b.k = v[6];
  b.xi = Vec3(v[7], v[8], v[9]);
  return b;
}

/// Stable order of `keys` (whole-mesh cells): each key's entries come from one
/// process, in its order.
std::vector<std::size_t> order_by_cell(const std::vector<Index>& keys) {
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  return order;
}

}  // namespace

SharedPass share_pass(const setup::Discretization& disc, std::span<const assembly::StretchedBond> mine,
                      double s_crit, const CellHolders& holders, bool distributed) {
  // Per cell e of this process's bonds (consecutive, ascending): the summary
  // entry (cell, count, Σ critical, Σ overshoot, largest stretch), and the
  // bonds for each process holding e.
  std::vector<double> summary;
  std::vector<la::Parcel> out;
  std::vector<double> own;
  for (std::size_t k = 0; k < mine.size();) {
    const Index e = mine[k].id.e;
    PERIMORPH_ASSERT(k == 0 || mine[k - 1].id.e < e, "a pass's bonds come by cell e, ascending");
    std::size_t end = k;
    double critical = 0.0, overshoot = 0.0, largest = 0.0;
    for (; end < mine.size() && mine[end].id.e == e; ++end) {
      const double c = assembly::energy_at_stretch(mine[end], s_crit);
      critical += c;
      overshoot += mine[end].energy - c;
      largest = std::max(largest, mine[end].stretch);
    }
    const Index ge = setup::global_cell(disc, e);
    summary.insert(summary.end(),
                   {static_cast<double>(ge), static_cast<double>(end - k), critical, overshoot, largest});
    const auto first = static_cast<std::ptrdiff_t>(own.size());
    for (std::size_t j = k; j < end; ++j) pack_bond(mine[j], ge, setup::global_cell(disc, mine[j].id.f), own);
    for (int p : holders.of(e)) {
      std::vector<double>& to = la::parcel_for(out, p);
      to.insert(to.end(), own.begin() + first, own.end());
    }
    k = end;
  }
  const std::vector<la::Parcel> in = distributed ? la::exchange(out) : std::vector<la::Parcel>{};
  const std::vector<double> all = distributed ? la::all_gather(summary) : summary;

  // The totals, summed over the cells in whole order, and where each cell's bonds begin.
  SharedPass pass;
  std::vector<Index> cells;
  for (std::size_t k = 0; k < all.size(); k += kSummary) cells.push_back(static_cast<Index>(all[k]));
  std::vector<Index> first_cell;
  std::vector<std::size_t> first_place;
  for (std::size_t i : order_by_cell(cells)) {
    const double* v = all.data() + i * kSummary;
    first_cell.push_back(cells[i]);
    first_place.push_back(pass.count);
    pass.count += static_cast<std::size_t>(v[1]);
    pass.dissipated += v[2];
    pass.overshoot += v[3];
    pass.max_stretch = std::max(pass.max_stretch, v[4]);
  }

  // This process's bonds and those sent to it, in whole order, with their places.
  std::vector<const double*> received;
  std::vector<Index> keys;
  auto collect = [&](const std::vector<double>& values) {
    for (std::size_t k = 0; k < values.size(); k += kBond) {
      received.push_back(values.data() + k);
      keys.push_back(static_cast<Index>(values[k]));
    }
  };
  collect(own);
  for (const la::Parcel& p : in) collect(p.values);
  Index previous = -1;
  std::size_t within = 0;
  for (std::size_t i : order_by_cell(keys)) {
    DecidedBond d{unpack_bond(received[i]), 0.0};
    d.critical = assembly::energy_at_stretch(d.bond, s_crit);
    const Index e = d.bond.id.e;
    within = e == previous ? within + 1 : 0;
    previous = e;
    const auto at = std::lower_bound(first_cell.begin(), first_cell.end(), e);
    PERIMORPH_ASSERT(at != first_cell.end() && *at == e, "a bond of a cell missing from the pass's summary");
    pass.place.push_back(first_place[static_cast<std::size_t>(at - first_cell.begin())] + within);
    pass.bonds.push_back(d);
  }
  return pass;
}

void gather_pass_on_process_zero(const setup::Discretization& disc,
                                 std::vector<assembly::StretchedBond>& bonds, std::vector<BondPoints>& points,
                                 bool distributed) {
  PERIMORPH_ASSERT(points.size() == bonds.size(), "a position for each bond");
  if (!distributed) return;
  std::vector<double> packed;
  packed.reserve(bonds.size() * kWritten);
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    const auto& b = bonds[k];
    pack_bond(b, setup::global_cell(disc, b.id.e), setup::global_cell(disc, b.id.f), packed);
    const auto& p = points[k];
    packed.insert(packed.end(), {p.g.x(), p.g.y(), p.g.z(), p.h.x(), p.h.y(), p.h.z()});
  }
  const std::vector<double> all = la::gather_on_process_zero(packed);
  std::vector<Index> keys;
  for (std::size_t k = 0; k < all.size(); k += kWritten) keys.push_back(static_cast<Index>(all[k]));
  bonds.clear();
  points.clear();
  for (std::size_t i : order_by_cell(keys)) {
    const double* v = all.data() + i * kWritten;
    bonds.push_back(unpack_bond(v));
    points.push_back({Vec3(v[10], v[11], v[12]), Vec3(v[13], v[14], v[15])});
  }
}

std::vector<std::pair<Vec3, Vec3>> failed_bond_points_over_processes(const setup::Discretization& piece,
                                                                     const RunState& state) {
  PERIMORPH_ASSERT(piece.piece && piece.nonlocal, "failed bond points are gathered from a non-local piece");
  PERIMORPH_ASSERT(state.failed_place.size() == state.failed_in_order.size(), "a place for each failed bond");
  const auto& pts = piece.nonlocal->points;
  std::vector<double> mine;
  for (std::size_t k = 0; k < state.failed_in_order.size(); ++k) {
    const auto& id = state.failed_in_order[k];
    if (!piece.piece->of_part(id.e)) continue;
    const Vec3 g = bonds::point_position(piece.mesh, pts, id.e, id.g),
               h = bonds::point_position(piece.mesh, pts, id.f, id.h);
    mine.insert(mine.end(),
                {static_cast<double>(state.failed_place[k]), g.x(), g.y(), g.z(), h.x(), h.y(), h.z()});
  }
  const std::vector<double> all = la::all_gather(mine);
  std::vector<std::pair<Vec3, Vec3>> out(state.failed_over_model);
  std::vector<char> seen(out.size(), 0);
  for (std::size_t k = 0; k < all.size(); k += 7) {
    const auto place = static_cast<std::size_t>(all[k]);
    PERIMORPH_ASSERT(place < out.size() && !seen[place],
                     "each failed bond given once, by its cell's process");
    seen[place] = 1;
    out[place] = {Vec3(all[k + 1], all[k + 2], all[k + 3]), Vec3(all[k + 4], all[k + 5], all[k + 6])};
  }
  PERIMORPH_ASSERT(std::all_of(seen.begin(), seen.end(), [](char s) { return s != 0; }),
                   "every failed bond given by its cell's process");
  return out;
}

}  // namespace perimorph::evolution
