#include "perimorph/evolution/damage_decisions.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>

namespace perimorph::evolution {

namespace {

constexpr std::size_t kSent = 3;     ///< doubles a change sent to a holder: whole point, d, old
constexpr std::size_t kSummary = 5;  ///< doubles a cell in the summary

}  // namespace

SharedDamage share_damage(const setup::Discretization& disc, std::span<const DamageChange> mine,
                          int points_per_cell, const CellHolders& holders, bool distributed) {
  const auto npts = static_cast<std::size_t>(points_per_cell);
  // Per cell of this process's changes (consecutive, ascending): the summary
  // entry (whole cell, count, Σ dissipated, Σ overshoot, largest growth),
  // and the changes for each process holding the cell.
  std::vector<double> summary;
  std::vector<la::Parcel> out;
  std::vector<double> sent;  // the cell's changes, packed once for its holders (most cells have none)
  for (std::size_t k = 0; k < mine.size();) {
    const std::size_t cell = mine[k].point / npts;
    PERIMORPH_ASSERT(k == 0 || mine[k - 1].point < mine[k].point, "an update's changes come in point order");
    const std::span<const int> to_holders = holders.of(static_cast<Index>(cell));
    std::size_t end = k;
    double dissipated = 0.0, overshoot = 0.0, largest = 0.0;
    sent.clear();
    for (; end < mine.size() && mine[end].point / npts == cell; ++end) {
      const DamageChange& ch = mine[end];
      dissipated += ch.dissipated;
      overshoot += ch.Y * (ch.d - ch.old) * ch.volume - ch.dissipated;
      largest = std::max(largest, ch.d - ch.old);
      if (!to_holders.empty()) sent.insert(sent.end(), {static_cast<double>(ch.whole), ch.d, ch.old});
    }
    summary.insert(summary.end(), {static_cast<double>(mine[k].whole / npts), static_cast<double>(end - k),
                                   dissipated, overshoot, largest});
    for (int p : to_holders) {
      std::vector<double>& to = la::parcel_for(out, p);
      to.insert(to.end(), sent.begin(), sent.end());
    }
    k = end;
  }
  const std::vector<la::Parcel> in = distributed ? la::exchange(out) : std::vector<la::Parcel>{};
  const std::vector<double> all = distributed ? la::all_gather(summary) : summary;

  // The totals, over the cells in whole order (each cell in one process's summary).
  SharedDamage shared;
  std::vector<std::pair<Index, std::size_t>> cells;  // whole cell, its entry
  for (std::size_t k = 0; k < all.size(); k += kSummary) cells.emplace_back(static_cast<Index>(all[k]), k);
  std::sort(cells.begin(), cells.end());
  for (const auto& [cell, k] : cells) {
    shared.count += static_cast<std::size_t>(all[k + 1]);
    shared.dissipated += all[k + 2];
    shared.overshoot += all[k + 3];
    shared.largest = std::max(shared.largest, all[k + 4]);
  }

  // The changes this process holds, in whole point order.
  shared.held.assign(mine.begin(), mine.end());
  for (const la::Parcel& p : in)
    for (std::size_t k = 0; k < p.values.size(); k += kSent) {
      const auto whole = static_cast<std::size_t>(p.values[k]);
      const Index c = setup::local_cell(disc, static_cast<Index>(whole / npts));
      PERIMORPH_ASSERT(c >= 0, "a damage change sent to a process without its cell");
      DamageChange ch{};
      ch.point = static_cast<std::size_t>(c) * npts + whole % npts;
      ch.whole = whole;
      ch.d = p.values[k + 1];
      ch.old = p.values[k + 2];
      shared.held.push_back(ch);
    }
  std::sort(shared.held.begin(), shared.held.end(),
            [](const DamageChange& a, const DamageChange& b) { return a.whole < b.whole; });
  return shared;
}

}  // namespace perimorph::evolution
