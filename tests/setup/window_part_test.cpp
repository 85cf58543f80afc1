// A part built on a window of its box (ModelPart::window, setup::part_window;
// issue 17, item 1), every part of 2, 3 and 4 played in one process: cut to
// its piece, it is the piece cut from the part built on the whole mesh, array
// for array and bit for bit — cells and nodes with their global numbers, the
// parts, the dof nodes' keys and owners, C at every local point, α bounds,
// points, graph rows, CG/DG flags — for a mixed CG/DG plate, a 3D ball of DG
// degree 0 with the partial volume, a matrix-free cube with node sets (P4's
// set-up, smaller), B4's hybrid cube (coarser), B1's bar
// and a plate without [nonlocal]. The window holds far fewer cells than the mesh.

#include "perimorph/casefile/parse_case.hpp"
#include "perimorph/mesh/box_window.hpp"
#include "perimorph/partition/grid_bisection.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/setup/discretization.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "support/model_cases.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

namespace perimorph {
namespace {

std::vector<testing::NamedCase> window_cases() {
  const std::string examples = std::string(PERIMORPH_SOURCE_DIR) + "/examples/";
  std::vector<testing::NamedCase> out;
  for (auto& c : testing::model_part_cases())
    if (setup::has_windows(c.config)) out.push_back(std::move(c));
  auto cube = casefile::parse_case_file(examples + "p4_peridigm_cube_3d/case.toml");
  cube.mesh.box.cells = {20, 20, 20};
  cube.mesh.box.upper = Vec3(20.0, 20.0, 20.0);
  cube.node_sets[1].lower = Vec3(17.1, 0.0, 0.0);
  cube.node_sets[1].upper = Vec3(20.0, 20.0, 20.0);
  out.push_back({"P4's cube, 20³ cells, matrix-free", cube});
  // B4's cube, hybrid (α from a region, CG), coarser points.
  auto b4 = casefile::parse_case_file(examples + "b4_cube_uniform_3d/case.toml");
  b4.mesh.box.cells = {18, 18, 18};
  b4.nonlocal.quadrature = 1;
  out.push_back({"b4's cube, 18³ cells, one point a cell", b4});
  out.push_back({"b1 bar", casefile::parse_case_file(examples + "b1_ghost_forces_1d/case.toml")});
  out.push_back(
      {"local plate (no [nonlocal])", testing::box_case(2, {14, 9, 1}, Vec3(7.0, 4.5, 0.0), 100.0, 0.3)});
  return out;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

void expect_same_piece(const setup::Discretization& got, const setup::Discretization& expected) {
  ASSERT_TRUE(got.piece && expected.piece);
  const auto &g = *got.piece, &e = *expected.piece;
  EXPECT_EQ(g.global_cell, e.global_cell);
  EXPECT_EQ(g.global_node, e.global_node);
  EXPECT_EQ(g.owner, e.owner);
  EXPECT_EQ(g.dofs.key, e.dofs.key);
  EXPECT_EQ(g.dofs.owned, e.dofs.owned);
  EXPECT_EQ(g.dofs.key_space, e.dofs.key_space);
  EXPECT_TRUE(same_bits(got.mesh.nodes(), expected.mesh.nodes()));
  EXPECT_EQ(got.mesh.connectivity(), expected.mesh.connectivity());
  EXPECT_EQ(got.mesh.node_sets, expected.mesh.node_sets);
  EXPECT_EQ(got.mesh.cell_sets, expected.mesh.cell_sets);
  EXPECT_EQ(got.mesh.cell_region, expected.mesh.cell_region);
  EXPECT_EQ(got.mesh.structure->box_cells, expected.mesh.structure->box_cells);
  EXPECT_EQ(got.computed_cells, expected.computed_cells);
  EXPECT_EQ(got.dofmap.num_dofs(), expected.dofmap.num_dofs());
  const Index cells = got.mesh.num_cells();
  ASSERT_EQ(cells, expected.mesh.num_cells());
  const int nv2 = got.stiffness.voigt() * got.stiffness.voigt();
  for (Index c = 0; c < cells; ++c) {
    EXPECT_EQ(got.dofmap.continuity(c), expected.dofmap.continuity(c));
    for (int q = 0; q < got.stiffness.points_per_cell(); ++q)
      EXPECT_EQ(std::memcmp(got.stiffness.at(c, q), expected.stiffness.at(c, q),
                            static_cast<std::size_t>(nv2) * sizeof(double)),
                0)
          << "cell " << g.global_cell[static_cast<std::size_t>(c)] << " point " << q;
  }
  ASSERT_EQ(got.nonlocal.has_value(), expected.nonlocal.has_value());
  if (!got.nonlocal) return;
  const auto &gn = *got.nonlocal, &en = *expected.nonlocal;
  EXPECT_EQ(gn.points.half_bound, en.points.half_bound);
  EXPECT_TRUE(same_bits(gn.points.cell_alpha_min, en.points.cell_alpha_min));
  EXPECT_TRUE(same_bits(gn.points.cell_alpha_max, en.points.cell_alpha_max));
  EXPECT_EQ(gn.points.stored, en.points.stored);
  EXPECT_TRUE(same_bits(gn.points.x, en.points.x));
  EXPECT_TRUE(same_bits(gn.points.weight, en.points.weight));
  EXPECT_TRUE(same_bits(gn.points.alpha, en.points.alpha));
  EXPECT_TRUE(same_bits(gn.points.half, en.points.half));
  EXPECT_EQ(gn.graph.offsets, en.graph.offsets);
  EXPECT_EQ(gn.graph.neighbors, en.graph.neighbors);
  EXPECT_EQ(gn.morph.purely_nonlocal, en.morph.purely_nonlocal);
}

TEST(WindowPart, CutsToThePieceOfThePartOnTheWholeMesh) {
  for (const auto& [name, config] : window_cases()) {
    SCOPED_TRACE(name);
    const auto whole = setup::build_discretization(config);
    const Index ncells = whole.mesh.num_cells();
    const std::vector<char> no_flags;
    const std::vector<char>& whole_flags = whole.nonlocal ? whole.nonlocal->morph.purely_nonlocal : no_flags;
    for (int parts : {2, 3, 4}) {
      SCOPED_TRACE(parts);
      const auto p = partition::coordinate_bisection(whole.mesh, parts);
      const partition::GridBisection grid = setup::grid_bisection(config, parts);
      testing::SharedFlags flags{&whole_flags, {}};
      Index in_windows = 0;
      for (int q = 0; q < parts; ++q) {
        const auto part = setup::build_discretization(config, {}, {parts, q, flags.share()});
        const auto expected = setup::cut_to_piece(part, p.owner, q, {});

        setup::MeshWindow window = setup::part_window(config, grid, q);
        const std::vector<int> owner = window.owner;
        // One process plays every part: "on any process" is the whole mesh's
        // check (made above), the bound over the processes is the whole mesh's,
        // and each window cell gets the whole model's CG/DG flag.
        window.any_over_processes = [](bool) { return true; };
        const double whole_bound = whole.nonlocal ? whole.nonlocal->points.half_bound : 0.0;
        window.max_over_processes = [whole_bound](double mine) {
          EXPECT_LE(mine, whole_bound);
          return whole_bound;
        };
        const auto cells = mesh::box_window_cells(setup::box_of(config), window.lo, window.hi);
        auto share = [&](std::vector<char> mine) {
          EXPECT_EQ(mine.size(), cells.size());
          for (std::size_t k = 0; k < mine.size(); ++k) {
            EXPECT_LE(mine[k], whole_flags[static_cast<std::size_t>(cells[k])]);
            mine[k] = whole_flags[static_cast<std::size_t>(cells[k])];
          }
          return mine;
        };
        const auto on_window = setup::build_discretization(config, {}, {parts, q, share, std::move(window)});
        ASSERT_TRUE(on_window.window != nullptr);
        EXPECT_EQ(on_window.window->global_cell, cells);
        for (std::size_t k = 0; k < cells.size(); ++k)
          EXPECT_EQ(owner[k], p.owner[static_cast<std::size_t>(cells[k])]) << "cell " << cells[k];
        in_windows += on_window.mesh.num_cells();
        const auto got = setup::cut_to_piece(on_window, owner, q, {});
        expect_same_piece(got, expected);
      }
      std::printf("%s, %d parts: the windows hold %.2f× the mesh's cells in all\n", name.c_str(), parts,
                  static_cast<double>(in_windows) / static_cast<double>(ncells));
    }
  }
}

/// A rebuild for a grown α (THEORY §5, [adaptivity]) from a piece whose
/// source is its window: the piece cut from the part rebuilt on the whole mesh.
/// The halo grows and stays within the window (cut_to_piece checks).
TEST(WindowPart, RebuildsForAGrownAlphaOnItsWindow) {
  // A long DG plate (3 parts along x), α = 1 in a disk at its left end.
  auto config = testing::box_case(2, {36, 12, 1}, Vec3(36.0, 12.0, 0.0), 100.0, 0.25);
  testing::add_nonlocal(config, casefile::KernelKind::constant, 1.2, 0.0, 2,
                        casefile::Discretization::discontinuous);
  config.alpha.regions = {testing::alpha_ball(Vec3(6.0, 6.0, 0.0), 3.5, 1.0)};
  const mesh::BoxSpec spec = setup::box_of(config);
  const auto whole = setup::build_discretization(config);
  // α = 1 in a disk across the first cut between parts (a ball the predictor would place).
  const auto alpha = whole.nonlocal->alpha.grown({{alpha::Ball{Vec3(12.0, 6.0, 0.0), 3.0}, 0.5}}, 2);
  const auto whole_grown = setup::rebuild_for_alpha(whole, alpha);
  // The whole model's flags the parts get: before the growth, then after it.
  std::vector<char> current = whole.nonlocal->morph.purely_nonlocal;
  EXPECT_NE(current, whole_grown.nonlocal->morph.purely_nonlocal) << "the growth changes CG/DG flags";
  const int parts = 3;
  const auto p = partition::coordinate_bisection(whole.mesh, parts);
  const partition::GridBisection grid = setup::grid_bisection(config, parts);
  bool grew = false, flags_changed = false;
  for (int q = 0; q < parts; ++q) {
    SCOPED_TRACE(q);
    current = whole.nonlocal->morph.purely_nonlocal;
    testing::SharedFlags flags{&current, {}};
    const auto part = setup::build_discretization(config, {}, {parts, q, flags.share()});
    setup::MeshWindow window = setup::part_window(config, grid, q);
    const std::vector<int> owner = window.owner;
    const auto cells =
        std::make_shared<const std::vector<Index>>(mesh::box_window_cells(spec, window.lo, window.hi));
    window.any_over_processes = [](bool) { return true; };
    window.max_over_processes = [&](double) { return whole.nonlocal->points.half_bound; };
    auto share = [cells, &current](std::vector<char> mine) {
      for (std::size_t k = 0; k < mine.size(); ++k) mine[k] = current[static_cast<std::size_t>((*cells)[k])];
      return mine;
    };
    auto on_window = setup::build_discretization(config, {}, {parts, q, share, std::move(window)});
    setup::Discretization piece = setup::cut_to_piece(on_window, owner, q, {});
    piece.source = setup::keep_source(std::move(on_window), owner);

    current = whole_grown.nonlocal->morph.purely_nonlocal;
    const auto got = setup::rebuild_piece_for_alpha(piece, alpha);
    const auto expected = setup::cut_to_piece(setup::rebuild_for_alpha(part, alpha), p.owner, q, {});
    EXPECT_GE(got.mesh.num_cells(), piece.mesh.num_cells());
    grew = grew || got.mesh.num_cells() > piece.mesh.num_cells();
    flags_changed =
        flags_changed || got.nonlocal->morph.purely_nonlocal != piece.nonlocal->morph.purely_nonlocal;
    expect_same_piece(got, expected);
    ASSERT_TRUE(got.source != nullptr);
    EXPECT_TRUE(got.source->part.window != nullptr) << "the next rebuild is on the window too";
  }
  EXPECT_TRUE(grew) << "a halo grows with α";
  EXPECT_TRUE(flags_changed) << "new DG cells";
}

}  // namespace
}  // namespace perimorph
