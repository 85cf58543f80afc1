// Bond failure on a process's piece of the model (issue 17, step 5) under
// mpiexec -n 1, 2 and 3: the bonds over the criterion at a displacement,
// each decided by the process of its cell on its piece, are those decided on
// the processes' parts of the whole model (the same bonds, figures and
// points, in the same order); broken on the pieces (each sent to the pieces
// holding its cell) they downdate K, A and the right-hand side to the parts'
// rows bit for bit, with the same energy, count, places in the whole order,
// crack area and per-cell fields.

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/floating_part_links.hpp"
#include "perimorph/evolution/floating_parts.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"
#include "perimorph/run/static_run.hpp"
#include "perimorph/setup/boundary_conditions.hpp"
#include "perimorph/setup/critical_stretch.hpp"
#include "perimorph/setup/piece_model.hpp"
#include "perimorph/system/constrained_system.hpp"
#include "perimorph/system/stiffness.hpp"
#include "perimorph/system/whole_numbering.hpp"
#include "support/floating_plate.hpp"
#include "support/model_cases.hpp"
#include "support/owned_rows.hpp"
#include "support/same_answer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

namespace perimorph {
namespace {

using testing::same_bits;

/// Cases with [fracture]: the fracture plate (CG, structured, a pre-crack
/// cut), the mixed CG/DG plate and the 3D ball of DG degree 0.
std::vector<testing::NamedCase> fracture_cases() {
  std::vector<testing::NamedCase> out;
  out.push_back({"fracture plate", casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) +
                                                             "/examples/fracture_plate_2d/case.toml")});
  for (auto& c : testing::model_part_cases())
    if (c.name.rfind("mixed", 0) == 0 || c.name.rfind("3D ball", 0) == 0) out.push_back(std::move(c));
  for (auto& c : out) {
    c.config.fracture.enabled = true;
    if (c.config.fracture.s_crit == 0.0 && c.config.fracture.G_c == 0.0) c.config.fracture.s_crit = 0.01;
    c.config.adaptivity.enabled = false;
  }
  return out;
}

/// u_x = a x |x| at every dof node, a such that the stretch reaches 3 s_crit
/// at the far end of the body: the bonds of its far two thirds fail.
evolution::RunState stretched(const setup::Discretization& model, double s_crit, double length) {
  evolution::RunState state(model);
  const double a = 1.5 * s_crit / length;
  const int dim = model.dim();
  for (Index n = 0; n < model.dofmap.num_nodes(); ++n) {
    const Vec3 x = model.dofmap.node_coordinate(model.mesh, n);
    state.u[static_cast<std::size_t>(n * dim)] = a * x.x() * std::abs(x.x());
  }
  return state;
}

/// The crack area of the whole model `whole` (built by this process alone)
/// with `failed` bonds, counted over every face (BondFailure::crack_area's
/// definition): the one-process answer, which the processes' count must give.
evolution::CrackArea crack_area_alone(const setup::Discretization& whole, const bonds::BrokenBonds& failed) {
  const auto& layout = *whole.mesh.structure;
  const int dim = whole.dim();
  std::array<double, 3> faces{};
  std::array<std::set<std::array<Index, 2>>, 3> columns;
  for (const auto& i : assembly::interface_bonds(whole.nonlocal_space(&failed))) {
    if (i.total == 0 || i.failed < i.total) continue;
    faces[static_cast<std::size_t>(i.axis)] += 1.0;
    const auto ijk = layout.cell_ijk(i.e);
    std::array<Index, 2> key{};
    for (int d = 0, k = 0; d < 3; ++d)
      if (d != i.axis) key[static_cast<std::size_t>(k++)] = ijk[static_cast<std::size_t>(d)];
    columns[static_cast<std::size_t>(i.axis)].insert(key);
  }
  evolution::CrackArea out;
  for (int axis = 0; axis < dim; ++axis) {
    double area = whole.scale;
    for (int d = 0; d < dim; ++d)
      if (d != axis) area *= layout.spacing[d];
    out.total += faces[static_cast<std::size_t>(axis)] * area;
    out.projected =
        std::max(out.projected, static_cast<double>(columns[static_cast<std::size_t>(axis)].size()) * area);
  }
  return out;
}

TEST(PieceFracture, DecidesAndBreaksTheBondsOfTheParts) {
  const int processes = la::world_size(), rank = la::world_rank();
  for (const auto& [name, config] : fracture_cases()) {
    SCOPED_TRACE(name);
    const setup::Discretization part = run::process_part(config);
    const auto owner = partition::coordinate_bisection(part.mesh, processes).owner;
    const setup::Discretization piece = setup::cut_to_piece(part, owner, rank, la::any_over_processes);
    double length = 0.0;
    for (Index n = 0; n < part.mesh.num_nodes(); ++n)
      length = std::max(length, std::abs(part.mesh.node(n).x()));
    const double s_crit = setup::critical_stretch(part);
    evolution::RunState on_part = stretched(part, s_crit, length),
                        on_piece = stretched(piece, s_crit, length);

    const evolution::BondFailure part_failure(part), piece_failure(piece);
    std::vector<evolution::BondPoints> part_points, piece_points;
    const auto expected = part_failure.select(on_part, &part_points);
    const auto got = piece_failure.select(on_piece, &piece_points);
    ASSERT_GT(expected.size(), 20U);
    ASSERT_EQ(got.size(), expected.size());
    ASSERT_EQ(piece_points.size(), got.size());
    ASSERT_EQ(part_points.size(), expected.size());
    // The same cells decide: the same bonds, in whole-mesh numbers on the piece.
    for (std::size_t k = 0; k < got.size(); ++k) {
      const auto &a = got[k], &b = expected[k];
      ASSERT_EQ(a.id.g, b.id.g) << k;
      ASSERT_EQ(a.id.h, b.id.h) << k;
      ASSERT_EQ(setup::global_cell(piece, a.id.e), b.id.e) << k;
      ASSERT_EQ(setup::global_cell(piece, a.id.f), b.id.f) << k;
      ASSERT_TRUE(same_bits(a.stretch, b.stretch) && same_bits(a.energy, b.energy) && same_bits(a.k, b.k) &&
                  same_bits(a.xi, b.xi))
          << k;
      ASSERT_TRUE(same_bits(piece_points[k].g, part_points[k].g) &&
                  same_bits(piece_points[k].h, part_points[k].h))
          << k;
    }
    // The whole pass, in the one-process order: the bonds a piece must hold
    // are those whose two cells it has.
    std::vector<double> ends;
    for (const auto& b : expected)
      ends.insert(ends.end(), {static_cast<double>(b.id.e), static_cast<double>(b.id.f)});
    const std::vector<double> all_ends = la::all_gather(ends);
    std::size_t held = 0;
    for (std::size_t k = 0; k < all_ends.size(); k += 2)
      if (setup::local_cell(piece, static_cast<Index>(all_ends[k])) >= 0 &&
          setup::local_cell(piece, static_cast<Index>(all_ends[k + 1])) >= 0)
        ++held;
    EXPECT_GT(held, 0U);
    if (processes == 1) {
      EXPECT_EQ(held, got.size());
      continue;  // one process runs on the whole model, not on a piece
    }

    // Broken on the parts' systems and on the pieces'.
    system::ConstrainedSystem part_system(part, system::assemble_stiffness_over_processes(part).K,
                                          setup::build_dirichlet(part), setup::build_external_force(part));
    system::ConstrainedSystem piece_system(piece, system::assemble_stiffness_over_processes(piece).K,
                                           setup::build_dirichlet(piece), setup::build_external_force(piece));
    const evolution::FailureEnergy e_part = part_failure.apply(expected, on_part, part_system);
    const evolution::FailureEnergy e_piece = piece_failure.apply(got, on_piece, piece_system);
    EXPECT_TRUE(same_bits(e_piece.dissipated, e_part.dissipated) &&
                same_bits(e_piece.overshoot, e_part.overshoot));
    EXPECT_TRUE(same_bits(on_piece.energy.dissipated, on_part.energy.dissipated));
    EXPECT_EQ(e_piece.count, all_ends.size() / 2);
    EXPECT_EQ(e_part.count, e_piece.count);
    EXPECT_TRUE(same_bits(e_piece.max_stretch, e_part.max_stretch));
    EXPECT_EQ(on_piece.failed_over_model, on_part.failed_over_model);
    // Each bond the piece holds (sent by its cell e's process), at its place
    // in the whole model's order (a part holds them all, in that order).
    ASSERT_EQ(on_piece.failed_in_order.size(), held);
    ASSERT_EQ(on_piece.failed_place.size(), held);
    ASSERT_EQ(on_part.failed_in_order.size(), on_part.failed_over_model);
    for (std::size_t k = 0; k < held; ++k) {
      const auto& a = on_piece.failed_in_order[k];
      const auto& b = on_part.failed_in_order[on_piece.failed_place[k]];
      ASSERT_TRUE(setup::global_cell(piece, a.e) == b.e && setup::global_cell(piece, a.f) == b.f &&
                  a.g == b.g && a.h == b.h)
          << "failed bond " << k << " at place " << on_piece.failed_place[k];
      if (k > 0) {
        ASSERT_LT(on_piece.failed_place[k - 1], on_piece.failed_place[k]);
      }
    }
    const testing::Rows K = testing::owned_rows(part_system.K()), A = testing::owned_rows(part_system.A());
    EXPECT_TRUE(testing::owned_rows(piece_system.K()) == K) << "K, process " << rank;
    EXPECT_TRUE(testing::owned_rows(piece_system.A()) == A) << "A, process " << rank;
    const auto rhs_part = part_system.rhs_unit().at_owned(part_system.owned_dofs());
    const auto rhs_piece = piece_system.rhs_unit().at_owned(piece_system.owned_dofs());
    ASSERT_EQ(rhs_piece.size(), rhs_part.size());
    for (std::size_t k = 0; k < rhs_part.size(); ++k) EXPECT_TRUE(same_bits(rhs_piece[k], rhs_part[k])) << k;
    // The same bonds are broken: none is left over the criterion on either.
    EXPECT_TRUE(part_failure.select(on_part).empty());
    EXPECT_TRUE(piece_failure.select(on_piece).empty());

    // More stretch: whole faces fail (bonds across them at every angle),
    // several in a column, on both sides of the parts' boundaries (2 is
    // enough in 3D and costs a third of 10). Structured meshes only: the
    // crack area is NaN on others.
    if (part.mesh.structure) {
      const double more = part.dim() == 3 ? 2.0 : 10.0;
      for (double& v : on_part.u) v *= more;
      for (double& v : on_piece.u) v *= more;
      part_failure.apply(part_failure.select(on_part), on_part, part_system);
      piece_failure.apply(piece_failure.select(on_piece), on_piece, piece_system);
    }

    // Crack area (collective) and the fields of the cells this process writes.
    const evolution::CrackArea area_part = part_failure.crack_area(on_part),
                               area_piece = piece_failure.crack_area(on_piece);
    EXPECT_TRUE(same_bits(area_piece.total, area_part.total) ||
                (std::isnan(area_part.total) && std::isnan(area_piece.total)));
    EXPECT_TRUE(same_bits(area_piece.projected, area_part.projected) ||
                (std::isnan(area_part.projected) && std::isnan(area_piece.projected)));
    if (part.mesh.structure) {
      // Faces of one column on several processes' cells counted once.
      const evolution::CrackArea alone =
          crack_area_alone(setup::build_discretization(config), on_part.failed);
      EXPECT_GT(alone.projected, 0.0);
      EXPECT_LT(alone.projected, alone.total) << "a column with several broken faces";
      EXPECT_TRUE(same_bits(area_piece.total, alone.total)) << area_piece.total << " " << alone.total;
      EXPECT_TRUE(same_bits(area_piece.projected, alone.projected))
          << area_piece.projected << " " << alone.projected;
    }
    std::vector<Index> part_cells, piece_cells;
    const auto mine = setup::cells_of_process(part, processes, rank);
    for (Index c = 0; c < part.mesh.num_cells(); ++c)
      if (mine[static_cast<std::size_t>(c)]) part_cells.push_back(c);
    const auto mine_on_piece = setup::cells_of_process(piece, processes, rank);
    for (Index c = 0; c < piece.mesh.num_cells(); ++c)
      if (mine_on_piece[static_cast<std::size_t>(c)]) piece_cells.push_back(c);
    ASSERT_EQ(piece_cells.size(), part_cells.size());
    const auto fields_part = part_failure.fields(on_part, part_cells);
    const auto fields_piece = piece_failure.fields(on_piece, piece_cells);
    for (std::size_t k = 0; k < part_cells.size(); ++k) {
      ASSERT_EQ(setup::global_cell(piece, piece_cells[k]), part_cells[k]);
      EXPECT_TRUE(same_bits(fields_piece.damage[k], fields_part.damage[k])) << "cell " << part_cells[k];
      EXPECT_TRUE(same_bits(fields_piece.dissipated[k], fields_part.dissipated[k]))
          << "cell " << part_cells[k];
    }
  }
}

// What bond failure cuts loose, found on the pieces in the dofs' and nodes'
// names (setup::dof_name: their keys) as on the parts, on the plate of
// floating_parts_test: cut through at x = 2 (its right half held along x
// only: a floating part), and with its last column stretched (its nodes left
// with no stiffness along x). The dofs left without stiffness, the floating
// parts and their pins are the parts', in the same order, from the whole
// graph's links and from those of the parts the held dofs may leave free
// (evolution::links_of_loosely_held_parts, what the run gathers).
TEST(PieceFracture, FindsWhatIsCutLooseAsTheParts) {
  const int processes = la::world_size(), rank = la::world_rank();
  if (processes == 1) GTEST_SKIP() << "one process runs on the whole model";
  auto config = testing::floating_plate(false);
  config.fracture.s_crit = 1e-12;
  const setup::Discretization part = run::process_part(config);
  const auto owner = partition::coordinate_bisection(part.mesh, processes).owner;
  const setup::Discretization piece = setup::cut_to_piece(part, owner, rank, la::any_over_processes);
  const system::WholeNumbering whole(piece.piece->dofs, piece.dim());
  // A name's whole dof, where this piece holds it (-1 elsewhere).
  auto whole_dof = [&](Index name) {
    const Index dof = setup::dof_of_name(piece, name);
    return dof < 0 ? Index{-1} : whole.whole_dofs_of(std::vector<Index>{dof})[0];
  };
  auto expect_same_names = [&](const std::vector<Index>& names, const std::vector<Index>& dofs,
                               const char* what) {
    ASSERT_EQ(names.size(), dofs.size()) << what;
    ASSERT_TRUE(std::is_sorted(names.begin(), names.end())) << what;
    std::size_t held = 0;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (const Index d = whole_dof(names[k]); d >= 0) {
        EXPECT_EQ(d, dofs[k]) << what << " " << k;
        ++held;
      }
    EXPECT_EQ(la::sum_over_processes({static_cast<double>(held)})[0] > 0.0, !names.empty())
        << what << ": none held anywhere";
  };

  for (const bool cut_through : {true, false}) {
    SCOPED_TRACE(cut_through ? "cut through at x = 2" : "last column stretched");
    auto stretched = [&](const setup::Discretization& model) {
      evolution::RunState state(model);
      if (cut_through)
        state.u = testing::jump_at_middle(model);
      else
        testing::stretch_last_column(model, state.u);
      return state;
    };
    evolution::RunState on_part = stretched(part), on_piece = stretched(piece);
    system::ConstrainedSystem part_system(part, system::assemble_stiffness_over_processes(part).K,
                                          setup::build_dirichlet(part), setup::build_external_force(part));
    system::ConstrainedSystem piece_system(piece, system::assemble_stiffness_over_processes(piece).K,
                                           setup::build_dirichlet(piece), setup::build_external_force(piece));
    const evolution::BondFailure part_failure(part), piece_failure(piece);
    part_failure.apply(part_failure.select(on_part), on_part, part_system);
    piece_failure.apply(piece_failure.select(on_piece), on_piece, piece_system);

    const std::vector<Index> part_detached = part_system.without_stiffness(part_system.last_downdated());
    const std::vector<Index> piece_detached = piece_system.without_stiffness(piece_system.last_downdated());
    if (!cut_through) {
      ASSERT_FALSE(part_detached.empty());
    }
    expect_same_names(piece_detached, part_detached, "dofs without stiffness");

    // Held: the prescribed dofs and those without stiffness (a piece's
    // prescribed dofs named and gathered).
    std::vector<Index> part_held(part_system.bc().dofs.begin(), part_system.bc().dofs.end());
    part_held.insert(part_held.end(), part_detached.begin(), part_detached.end());
    std::sort(part_held.begin(), part_held.end());
    std::vector<double> mine;
    for (Index d : piece_system.bc().dofs) mine.push_back(static_cast<double>(setup::dof_name(piece, d)));
    std::vector<Index> piece_held;
    for (double v : la::all_gather(mine)) piece_held.push_back(static_cast<Index>(v));
    piece_held.insert(piece_held.end(), piece_detached.begin(), piece_detached.end());
    std::sort(piece_held.begin(), piece_held.end());
    piece_held.erase(std::unique(piece_held.begin(), piece_held.end()), piece_held.end());

    const la::DofValuesAt part_force = [&](std::span<const Index> dofs) {
      return part_system.applied_force_at(dofs);
    };
    const la::DofValuesAt piece_force = [&](std::span<const Index> names) {
      std::vector<Index> dofs(names.size());
      for (std::size_t k = 0; k < names.size(); ++k) dofs[k] = setup::dof_of_name(piece, names[k]);
      return piece_system.applied_force_at(dofs);
    };
    const auto part_links = evolution::stiffness_links_over_processes(part, part_failure.space(on_part));
    std::vector<Vec3> positions;
    const auto piece_links =
        evolution::stiffness_links_over_processes(piece, piece_failure.space(on_piece), &positions);
    const evolution::FloatingParts expected =
        evolution::find_floating_parts(part, part_links, part_held, part_force);
    const evolution::FloatingParts got =
        evolution::find_floating_parts(piece, piece_links, piece_held, piece_force, positions);
    if (cut_through) {
      ASSERT_GE(expected.parts, 1);
    }
    EXPECT_EQ(got.parts, expected.parts);
    expect_same_names(got.pins, expected.pins, "pins");

    // Given only the links of the parts the held dofs may leave free (the
    // right half, held along x only, when cut through): the same parts and
    // pins, without the held body's links.
    std::vector<Vec3> loose_positions;
    const auto loose_links = evolution::links_of_loosely_held_parts(piece, piece_failure.space(on_piece),
                                                                    piece_held, &loose_positions);
    const evolution::FloatingParts loose =
        evolution::find_floating_parts(piece, loose_links, piece_held, piece_force, loose_positions);
    EXPECT_EQ(loose.parts, expected.parts);
    expect_same_names(loose.pins, expected.pins, "pins from the loosely held parts");
    EXPECT_LT(loose_links.size(), piece_links.size()) << "the held body's links are gathered too";
    std::vector<Index> loose_nodes;  // each node once, as in the whole graph's links
    for (std::size_t k = 0; k < loose_links.size(); k += 2) loose_nodes.push_back(loose_links[k]);
    std::sort(loose_nodes.begin(), loose_nodes.end());
    EXPECT_EQ(std::adjacent_find(loose_nodes.begin(), loose_nodes.end()), loose_nodes.end())
        << "a node twice";
    if (cut_through) {
      // The right half's nodes: those of its cells (x > 2) and no other.
      for (std::size_t k = 0; k < loose_positions.size(); ++k) EXPECT_GE(loose_positions[k].x(), 2.0) << k;
      EXPECT_GT(loose_links.size(), piece_links.size() / 4);
    }
  }
}

/// The bytes of a file ("" if it cannot be read).
std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A run with bond failure on the pieces (run::process_model) against the
// run on the parts: the fracture plate (30 increments, its crack running)
// and the plate cut through by its pulled edge (parts cut free, nodes left
// without stiffness, motions inside cells: PartSupport by dof names). The
// same records (energies, reactions, failed bonds, floating parts, cell
// mechanisms, crack area), the same failed-bond positions, and each
// process's VTU pieces and the failed-bond CSV byte for byte, on 2
// processes; on 3 the same counts and the values within 1e-10 of the largest.
TEST(PieceFracture, RunsAsOnTheParts) {
  namespace fs = std::filesystem;
  const int processes = la::world_size(), rank = la::world_rank();
  if (processes == 1) GTEST_SKIP() << "one process runs on the whole model";
  const fs::path root = fs::temp_directory_path() / ("perimorph_piece_fracture_" + std::to_string(processes));
  if (rank == 0) fs::remove_all(root);
  (void)la::any_over_processes(false);  // every process waits for the folder to be cleared
  auto plate = testing::plate_cut_in_band();
  auto fracture_plate =
      casefile::parse_case_file(std::string(PERIMORPH_SOURCE_DIR) + "/examples/fracture_plate_2d/case.toml");
  fracture_plate.loading.factors = {1.0 / 30, 2.0 / 30};  // its first two: a crack starts in the second
  const std::vector<testing::NamedCase> cases = {{"fracture plate", fracture_plate},
                                                 {"plate cut free", plate}};
  const bool bitwise = processes <= 2;
  for (const auto& [name, config] : cases) {
    SCOPED_TRACE(name);
    const run::RunOptions on_part{(root / name / "part").string(), true},
        on_piece{(root / name / "piece").string(), true};
    const setup::Discretization part = run::process_part(config);
    const setup::Discretization piece = run::process_model(config);
    ASSERT_TRUE(piece.piece != nullptr);
    const run::RunSummary expected = run::run_static(part, on_part);
    const run::RunSummary got = run::run_static(piece, on_piece);
    ASSERT_EQ(got.history.size(), expected.history.size());
    ASSERT_GT(expected.history.back().bonds_broken, 0U);
    if (name == "plate cut free") {
      EXPECT_GT(expected.history.back().floating_parts, 0U);
      EXPECT_GT(expected.history.back().cell_mechanisms, 0U);
    }
    testing::expect_same_fracture_run(got, expected, bitwise);
    if (!bitwise) continue;
    const std::string mine = "_p" + std::to_string(rank) + ".vtu";
    int compared = 0;
    for (const auto& entry : fs::directory_iterator(on_part.output_directory)) {
      const std::string file = entry.path().filename().string();
      if (!(file.ends_with(mine) || (rank == 0 && (file.ends_with(".pvtu") || file.ends_with(".pvd") ||
                                                   file.ends_with("_failed_bonds.csv")))))
        continue;
      const std::string theirs = bytes_of(entry.path());
      EXPECT_FALSE(theirs.empty()) << file;
      EXPECT_TRUE(bytes_of(fs::path(on_piece.output_directory) / file) == theirs) << file;
      ++compared;
    }
    EXPECT_GE(compared, 2) << "VTU pieces";
  }
}

}  // namespace
}  // namespace perimorph
