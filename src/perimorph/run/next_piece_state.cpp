#include "perimorph/run/next_piece_state.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/neighbour_exchange.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <algorithm>
#include <cstddef>
#include <set>
#include <utility>

namespace perimorph::run {

namespace {

using Placed = std::pair<std::size_t, bonds::BondId>;  ///< a failed bond and its place in the whole order

constexpr std::size_t kBond = 5;  ///< doubles a bond: place, e, f (global), g, h

std::size_t points_per_cell(const setup::Discretization& disc) {
  return disc.damage ? static_cast<std::size_t>(disc.damage->points_per_cell) : 0;
}

/// What this process sends a process that asks for the state of `asked`
/// (global cells, ascending): the failed bonds it decided with a cell among
/// them, then the damage history of those of its part's cells that is not
/// zero. [bonds, bonds × (place, e, f, g, h), cells × (cell, history)].
std::vector<double> answer(const setup::Discretization& disc, const evolution::RunState& state,
                           const std::vector<double>& asked) {
  const setup::PieceNumbers& piece = *disc.piece;
  auto is_asked = [&](Index local) {
    return std::binary_search(asked.begin(), asked.end(),
                              static_cast<double>(piece.global_cell[static_cast<std::size_t>(local)]));
  };
  std::vector<double> out{0.0};
  for (std::size_t k = 0; k < state.failed_in_order.size(); ++k) {
    const bonds::BondId& id = state.failed_in_order[k];
    if (!piece.of_part(id.e) || !(is_asked(id.e) || is_asked(id.f))) continue;
    out.insert(out.end(), {static_cast<double>(state.failed_place[k]),
                           static_cast<double>(setup::global_cell(disc, id.e)),
                           static_cast<double>(setup::global_cell(disc, id.f)), static_cast<double>(id.g),
                           static_cast<double>(id.h)});
    out[0] += 1.0;
  }
  const std::size_t n = points_per_cell(disc);
  if (n == 0) return out;
  for (double g : asked) {
    const Index c = piece.local_cell(static_cast<Index>(g));
    if (c < 0 || !piece.of_part(c)) continue;
    const auto first = state.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * n);
    if (std::all_of(first, first + static_cast<std::ptrdiff_t>(n), [](double d) { return d == 0.0; }))
      continue;
    out.push_back(g);
    out.insert(out.end(), first, first + static_cast<std::ptrdiff_t>(n));
  }
  return out;
}

}  // namespace

evolution::RunState next_piece_state(const setup::Discretization& before, const setup::Discretization& after,
                                     const evolution::RunState& state) {
  PERIMORPH_ASSERT(before.piece && after.piece, "next_piece_state: two pieces of the model");
  const setup::PieceNumbers &was = *before.piece, &now = *after.piece;
  PERIMORPH_ASSERT(was.part == now.part && now.part == la::world_rank(),
                   "next_piece_state: the pieces of this process's part");
  evolution::RunState out(after);
  out.take_progress(state);
  out.failed_over_model = state.failed_over_model;
  auto now_of = [&](Index c) {  // before's local cell c in after's numbers
    const Index local = now.local_cell(setup::global_cell(before, c));
    PERIMORPH_ASSERT(local >= 0, "next_piece_state: the next piece lacks a cell of this one");
    return local;
  };

  // The cells new to the piece, asked of every process whose part has a cell
  // in it: one of them decided each failed bond of a new cell.
  std::vector<double> fresh;
  std::set<int> parts;
  for (Index c = 0; c < after.mesh.num_cells(); ++c) {
    const Index g = now.global_cell[static_cast<std::size_t>(c)];
    if (was.local_cell(g) < 0) fresh.push_back(static_cast<double>(g));
    if (!now.of_part(c)) parts.insert(now.owner[static_cast<std::size_t>(c)]);
  }
  std::vector<la::Parcel> asks;
  if (!fresh.empty())
    for (int p : parts) asks.push_back({p, fresh});
  std::vector<la::Parcel> answers;
  for (const la::Parcel& ask : la::exchange(asks))
    answers.push_back({ask.process, answer(before, state, ask.values)});
  answers = la::exchange(answers);

  // The failed bonds: this piece's and the new ones, in the whole order.
  std::vector<Placed> failed;
  for (std::size_t k = 0; k < state.failed_in_order.size(); ++k) {
    const bonds::BondId& id = state.failed_in_order[k];
    failed.push_back({state.failed_place[k], {now_of(id.e), now_of(id.f), id.g, id.h}});
  }
  const std::size_t n = points_per_cell(after);
  std::vector<std::pair<Index, const double*>> history;  // a new cell's, from its part's process
  for (const la::Parcel& a : answers) {
    const std::size_t bonds = static_cast<std::size_t>(a.values.at(0)), end = 1 + bonds * kBond;
    PERIMORPH_ASSERT(end <= a.values.size() && (a.values.size() - end) % (n + 1) == 0,
                     "next_piece_state: a malformed answer");
    for (std::size_t k = 1; k < end; k += kBond) {
      const Index e = now.local_cell(static_cast<Index>(a.values[k + 1])),
                  f = now.local_cell(static_cast<Index>(a.values[k + 2]));
      if (e < 0 || f < 0) continue;  // a bond of a new cell to a cell this piece lacks
      failed.push_back({static_cast<std::size_t>(a.values[k]),
                        {e, f, static_cast<int>(a.values[k + 3]), static_cast<int>(a.values[k + 4])}});
    }
    for (std::size_t k = end; k < a.values.size(); k += n + 1)
      history.emplace_back(now.local_cell(static_cast<Index>(a.values[k])), &a.values[k + 1]);
  }
  std::sort(failed.begin(), failed.end(), [](const Placed& a, const Placed& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < failed.size(); ++k) {
    PERIMORPH_ASSERT(k == 0 || failed[k - 1].first < failed[k].first,
                     "next_piece_state: two failed bonds in one place");
    out.failed.add(failed[k].second);
    out.failed_in_order.push_back(failed[k].second);
    out.failed_place.push_back(failed[k].first);
  }

  // D of the part's cells (it holds all their bonds).
  for (const auto& [c, d] : state.cell_dissipated)
    if (was.of_part(c)) out.cell_dissipated[now_of(c)] = d;

  // The damage history: the cells this piece held, then the new ones.
  if (n > 0) {
    for (Index c = 0; c < before.mesh.num_cells(); ++c)
      std::copy_n(state.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * n), n,
                  out.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(now_of(c)) * n));
    for (const auto& [c, values] : history) {
      PERIMORPH_ASSERT(c >= 0, "next_piece_state: a history for a cell this piece lacks");
      std::copy_n(values, n,
                  out.history.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(c) * n));
    }
  }
  return out;
}

}  // namespace perimorph::run
