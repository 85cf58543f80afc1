// The failed-bond store (bonds/broken_bonds.hpp): what the pair kernel and
// the stretch pass read, and a size that follows the failures, not the model.

#include "perimorph/bonds/broken_bonds.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace perimorph {
namespace {

TEST(BrokenBonds, KeepsEachBondOnceUnderItsCellPairSorted) {
  bonds::BrokenBonds b(10, 4);
  EXPECT_TRUE(b.add({7, 3, 2, 1}));   // stored as (3, 7, 1, 2)
  EXPECT_FALSE(b.add({3, 7, 1, 2}));  // the same bond
  EXPECT_TRUE(b.add({3, 7, 0, 3}));
  EXPECT_TRUE(b.add({5, 5, 2, 0}));  // within a cell: both orders stored
  EXPECT_EQ(b.size(), 3U);

  const auto p = b.pair(3, 7);
  EXPECT_EQ(std::vector<std::uint32_t>(p.begin(), p.end()),
            (std::vector<std::uint32_t>{0 * 4 + 3, 1 * 4 + 2}));
  const auto s = b.pair(5, 5);
  EXPECT_EQ(std::vector<std::uint32_t>(s.begin(), s.end()),
            (std::vector<std::uint32_t>{0 * 4 + 2, 2 * 4 + 0}));
  EXPECT_TRUE(b.pair(3, 5).empty());  // both cells touched, no bond between them
  EXPECT_TRUE(b.pair(0, 1).empty());

  EXPECT_TRUE(b.contains({7, 3, 2, 1}));
  EXPECT_TRUE(b.contains({5, 5, 0, 2}));
  EXPECT_FALSE(b.contains({3, 7, 2, 1}));
  for (Index c = 0; c < 10; ++c) EXPECT_EQ(b.touches(c), c == 3 || c == 5 || c == 7) << "cell " << c;
}

// Every process holds the whole set (issue 17): an empty store of a model of
// 10⁶ cells costs a bit a cell, and a failure the pair's codes and hash node,
// where a map per cell cost 52 bytes a cell.
TEST(BrokenBonds, HoldsABitACellAndWhatHasFailed) {
  const Index cells = 1'000'000;
  bonds::BrokenBonds b(cells, 8);
  EXPECT_LE(b.bytes(), static_cast<std::size_t>(cells) / 8 + 64);
  for (Index e = 0; e < 1000; ++e) b.add({e, e + 1, 0, 1});
  EXPECT_LE(b.bytes(), static_cast<std::size_t>(cells) / 8 + 1000 * 64 + 8 * 2048);
  EXPECT_TRUE(b.touches(1000));
  EXPECT_FALSE(b.touches(1001));
}

}  // namespace
}  // namespace perimorph
