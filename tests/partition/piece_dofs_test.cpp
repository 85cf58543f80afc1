// What a piece decides about its dof nodes alone (partition/piece_dofs.hpp),
// checked by playing every process in turn: each part's piece (its cells and
// their node neighbours, cells_near_part) owns exactly the nodes
// dof_numbering gives the part, its keys name the same nodes as every other
// piece's, and numbering the owned nodes in key order after the lower parts'
// gives dof_numbering's numbers, ghosts included.

#include "perimorph/partition/piece_dofs.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/mesh/box.hpp"
#include "perimorph/mesh/part_mesh.hpp"
#include "perimorph/partition/dof_layout.hpp"

#include "support/pieces.hpp"

#include <gtest/gtest.h>

#include <map>

namespace perimorph {
namespace {

/// Each dof node's key in the whole model's dof map, by the same rule.
std::vector<Index> whole_keys(const mesh::Mesh& whole, const dofs::DofMap& dm) {
  std::vector<Index> key(static_cast<std::size_t>(dm.num_nodes()), -1);
  const int k = whole.nodes_per_cell();
  for (Index c = 0; c < whole.num_cells(); ++c) {
    const auto nodes = dm.cell_nodes(c);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      key[static_cast<std::size_t>(nodes[a])] = dm.continuity(c) == dofs::Continuity::continuous
                                                    ? whole.cell(c)[a]
                                                    : whole.num_nodes() + c * k + static_cast<Index>(a);
  }
  return key;
}

void expect_pieces_give_the_whole_numbering(const mesh::Mesh& whole) {
  const auto flags = testing::mixed_continuity(whole);
  const dofs::DofMap dm(whole, whole.dim(), flags);
  const auto key = whole_keys(whole, dm);
  ASSERT_TRUE(std::is_sorted(key.begin(), key.end())) << "the whole dof map is in key order";
  for (int parts : {1, 2, 3, 4}) {
    SCOPED_TRACE(parts);
    const auto p = partition::coordinate_bisection(whole, parts);
    const auto layout = partition::dof_numbering(dm, p);
    std::vector<testing::TestPiece> pieces;
    for (int part = 0; part < parts; ++part) pieces.push_back(testing::make_piece(whole, flags, p, part, 2));
    // The play of piece_distribution's two collective steps.
    std::map<Index, Index> number_of_key;
    Index next = 0;
    for (int part = 0; part < parts; ++part) {
      const auto& d = pieces[static_cast<std::size_t>(part)].dofs;
      EXPECT_EQ(d.num_owned(), layout.owned_nodes(part));
      EXPECT_EQ(next, layout.part_offsets[static_cast<std::size_t>(part)]);
      for (std::size_t n = 0; n < d.key.size(); ++n) {
        if (d.owned[n]) {
          EXPECT_TRUE(number_of_key.emplace(d.key[n], next++).second) << "owned twice";
        }
      }
    }
    ASSERT_EQ(next, dm.num_nodes());
    std::map<Index, Index> whole_node_of_key;
    for (Index n = 0; n < dm.num_nodes(); ++n) whole_node_of_key[key[static_cast<std::size_t>(n)]] = n;
    for (int part = 0; part < parts; ++part) {
      const auto& d = pieces[static_cast<std::size_t>(part)].dofs;
      for (std::size_t n = 0; n < d.key.size(); ++n) {
        const Index w = whole_node_of_key.at(d.key[n]);
        EXPECT_EQ(number_of_key.at(d.key[n]), layout.to_distributed[static_cast<std::size_t>(w)]);
        EXPECT_EQ(d.owned[n] != 0, layout.node_owner[static_cast<std::size_t>(w)] == part);
      }
    }
  }
}

TEST(PieceDofs, PiecesNumberTheirNodesAsTheWholeModelOn1To4Parts2D) {
  expect_pieces_give_the_whole_numbering(mesh::make_box({2, Vec3(0, 0, 0), Vec3(9, 7, 0), {9, 7, 1}}));
}

TEST(PieceDofs, PiecesNumberTheirNodesAsTheWholeModelOn1To4Parts3D) {
  expect_pieces_give_the_whole_numbering(mesh::make_box({3, Vec3(0, 0, 0), Vec3(5, 4, 3), {5, 4, 3}}));
}

TEST(PieceDofs, RefusesOwnersOfAnotherLength) {
  const auto whole = mesh::make_box({2, Vec3(0, 0, 0), Vec3(2, 2, 0), {2, 2, 1}});
  const auto pm = mesh::part_mesh(whole, std::vector<Index>{0, 1, 2, 3});
  const dofs::DofMap local(pm.mesh, 2);
  EXPECT_THROW(partition::piece_dofs(local, pm, std::vector<int>{0, 0, 0}, 0, whole.num_nodes(), 4), Error);
}

TEST(PieceDofs, KeysBeyond32BitIndicesAreRefusedWithTheSizes) {
  const auto whole = mesh::make_box({2, Vec3(0, 0, 0), Vec3(1, 1, 0), {1, 1, 1}});
  const auto pm = mesh::part_mesh(whole, std::vector<Index>{0});
  const dofs::DofMap local(pm.mesh, 2);
  try {
    partition::piece_dofs(local, pm, std::vector<int>{0}, 0, 4, 600'000'000);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("600000000 cells"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace perimorph
