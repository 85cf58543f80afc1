#include "perimorph/system/piece_distribution.hpp"

#include "perimorph/la/key_exchange.hpp"

namespace perimorph::system {

std::shared_ptr<const la::Distribution> piece_distribution(const partition::PieceDofs& piece) {
  auto d = std::make_shared<la::Distribution>();
  const Index owned = piece.num_owned();
  d->begin = la::offset_over_processes(owned);
  d->end = d->begin + owned;
  const std::size_t nodes = piece.key.size();
  d->to_distributed.assign(nodes, -1);
  // Owned nodes in local order, which is the keys' (the whole model's) order.
  std::vector<Index> owned_keys, owned_numbers, ghost_keys;
  owned_keys.reserve(static_cast<std::size_t>(owned));
  owned_numbers.reserve(static_cast<std::size_t>(owned));
  Index next = d->begin;
  for (std::size_t n = 0; n < nodes; ++n) {
    if (piece.owned[n]) {
      d->to_distributed[n] = next;
      owned_keys.push_back(piece.key[n]);
      owned_numbers.push_back(next++);
    } else {
      ghost_keys.push_back(piece.key[n]);
    }
  }
  const std::vector<Index> ghosts =
      la::values_of_keys(owned_keys, owned_numbers, ghost_keys, piece.key_space);
  std::size_t g = 0;
  for (std::size_t n = 0; n < nodes; ++n)
    if (!piece.owned[n]) d->to_distributed[n] = ghosts[g++];
  return d;
}

}  // namespace perimorph::system
