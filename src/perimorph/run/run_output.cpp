#include "perimorph/run/run_output.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/grid.hpp"
#include "perimorph/io/pvtu_writer.hpp"
#include "perimorph/io/vtu_writer.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/partition/partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <numeric>
#include <utility>

namespace perimorph::run {

namespace {

/// Voigt (engineering shear) to a row-major 3×3 tensor; `engineering` halves shears.
std::array<double, 9> voigt_to_tensor(const double* v, int dim, bool engineering) {
  const double h = engineering ? 0.5 : 1.0;
  std::array<double, 9> t{};
  if (dim == 1) {
    t[0] = v[0];
  } else if (dim == 2) {
    t[0] = v[0];
    t[4] = v[1];
    t[1] = t[3] = h * v[2];
  } else {
    t[0] = v[0];
    t[4] = v[1];
    t[8] = v[2];
    t[5] = t[7] = h * v[3];
    t[2] = t[6] = h * v[4];
    t[1] = t[3] = h * v[5];
  }
  return t;
}

io::VtkCell vtk_cell(int dim) {
  return dim == 1 ? io::VtkCell::line : dim == 2 ? io::VtkCell::quad : io::VtkCell::hexahedron;
}

}  // namespace

RunOutput::RunOutput(const setup::Discretization& model, std::string directory, std::string basename,
                     std::vector<std::string> reaction_names, const OutputPosition* resume)
    : directory_(std::move(directory)),
      basename_(std::move(basename)),
      dim_(model.dim()),
      fracture_(model.config.fracture.enabled),
      adaptive_(model.config.adaptivity.enabled),
      damage_(model.damage.has_value()),
      vtu_(model.config.output.vtu) {
  // Process 0 writes (every process holds the whole state); every process
  // learns whether it could (la::on_process_zero).
  la::on_process_zero([&] {
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec)
      throw OutputError(fmt::format("cannot create output directory '{}': {}", directory_, ec.message()));
    lock_ = std::make_unique<io::OutputLock>(directory_, basename_);
    std::vector<std::string> columns{"increment", "load_factor"};
    const char* axes = "xyz";
    for (const auto& name : reaction_names)
      for (int d = 0; d < dim_; ++d) columns.push_back(fmt::format("reaction_{}_{}", name, axes[d]));
    for (const char* c :
         {"strain_energy", "external_work", "solver_iterations", "relative_residual", "wall_time"})
      columns.emplace_back(c);
    if (fracture_)
      for (const char* c : {"dissipated_energy", "dissipated_increment", "overshoot_energy",
                            "released_energy", "bonds_broken", "bonds_broken_increment", "break_iterations",
                            "crack_area", "broken_face_area", "floating_parts", "cell_mechanisms"})
        columns.emplace_back(c);
    if (damage_) {
      if (!fracture_) columns.insert(columns.end(), {"overshoot_energy", "released_energy"});
      for (const char* c : {"damage_dissipated_energy", "damage_iterations", "damage_newton_steps",
                            "damaged_points", "critical_points", "max_damage"})
        columns.emplace_back(c);
    }
    if (adaptive_)
      for (const char* c :
           {"dofs", "dg_cells", "nonlocal_cells", "alpha_balls", "model_energy_change", "remodel_time"})
        columns.emplace_back(c);
    auto table = [&](std::string path, std::vector<std::string> cols, std::size_t OutputPosition::*rows) {
      return resume ? std::make_unique<io::CsvTable>(std::move(path), std::move(cols), resume->*rows)
                    : std::make_unique<io::CsvTable>(std::move(path), std::move(cols));
    };
    csv_ = table(csv_path(), std::move(columns), &OutputPosition::rows);
    if (adaptive_)
      alpha_csv_ = table((std::filesystem::path(directory_) / (basename_ + "_alpha.csv")).string(),
                         std::vector<std::string>{"increment", "cell", "x", "y", "z", "radius", "transition",
                                                  "predicted", "critical_damage"},
                         &OutputPosition::alpha_rows);
    if (fracture_)
      failures_csv_ =
          table(failures_csv_path(),
                std::vector<std::string>{"increment", "iteration", "bonds_failed", "dissipated_energy",
                                         "overshoot_energy", "max_stretch_ratio", "solver_iterations",
                                         "preconditioner_rebuilt", "wall_time"},
                &OutputPosition::failure_rows);
    if (fracture_ && model.config.output.failed_bonds)
      failed_bonds_csv_ =
          table((std::filesystem::path(directory_) / (basename_ + "_failed_bonds.csv")).string(),
                std::vector<std::string>{"increment", "iteration", "xg", "yg", "zg", "xh", "yh", "zh",
                                         "stretch", "dissipated_energy", "overshoot_energy"},
                &OutputPosition::failed_bond_rows);
    if (model.config.output.vtu)
      pvd_ = resume ? std::make_unique<io::PvdCollection>(pvd_path(), resume->pvd)
                    : std::make_unique<io::PvdCollection>(pvd_path());
  });
}

OutputPosition RunOutput::position() const {
  OutputPosition p;
  if (!csv_) return p;
  p.rows = csv_->rows();
  if (alpha_csv_) p.alpha_rows = alpha_csv_->rows();
  if (failures_csv_) p.failure_rows = failures_csv_->rows();
  if (failed_bonds_csv_) p.failed_bond_rows = failed_bonds_csv_->rows();
  if (pvd_) p.pvd = pvd_->entries();
  return p;
}

std::string RunOutput::csv_path() const {
  return (std::filesystem::path(directory_) / (basename_ + ".csv")).string();
}
std::string RunOutput::pvd_path() const {
  return (std::filesystem::path(directory_) / (basename_ + ".pvd")).string();
}
std::string RunOutput::vtu_path(int increment) const {
  return (std::filesystem::path(directory_) /
          fmt::format("{}_{:04d}.{}", basename_, increment, la::world_size() == 1 ? "vtu" : "pvtu"))
      .string();
}
std::string RunOutput::failures_csv_path() const {
  return fracture_ ? (std::filesystem::path(directory_) / (basename_ + "_failures.csv")).string() : "";
}

io::UnstructuredGrid RunOutput::increment_grid(const setup::Discretization& model, std::span<const double> u,
                                               const evolution::FractureFields& fracture,
                                               const evolution::DamageFields& damage,
                                               std::span<const Index> listed) const {
  const auto& dm = model.dofmap;
  const bool selected = !listed.empty();
  std::vector<Index> every;
  if (!selected) {
    every.resize(static_cast<std::size_t>(dm.num_cells()));
    std::iota(every.begin(), every.end(), Index{0});
  }
  const std::span<const Index> cells = selected ? listed : std::span<const Index>(every);
  for (Index c : cells)  // their stresses need their C
    PERIMORPH_ASSERT(model.computed_cells.empty() || model.computed_cells[static_cast<std::size_t>(c)],
                     "the output writes a cell whose morphed C this process did not compute");
  io::UnstructuredGrid grid;
  grid.nodes_per_cell = model.mesh.nodes_per_cell();
  grid.cell_type = vtk_cell(dim_);
  // Points are the dof nodes of the cells written, ascending: for the whole
  // model every dof node (point n is node n), for a piece its cells' nodes,
  // found by search (no array as long as the model's). A DG degree 0 cell is
  // drawn with its own corner points, all carrying its centroid node's displacement.
  std::vector<Index> point_dof_node;
  if (!selected) {
    point_dof_node.resize(static_cast<std::size_t>(dm.num_nodes()));
    std::iota(point_dof_node.begin(), point_dof_node.end(), Index{0});
  } else {
    point_dof_node = dm.dof_nodes_of_cells(cells);
  }
  const auto node_points = static_cast<std::ptrdiff_t>(point_dof_node.size());
  auto point_of_node = [&](Index n) {
    if (!selected) return n;
    const auto first = point_dof_node.begin();
    return static_cast<Index>(std::lower_bound(first, first + node_points, n) - first);
  };
  for (Index n : point_dof_node) grid.points.push_back(dm.node_coordinate(model.mesh, n));
  for (Index c : cells) {
    const auto nodes = dm.cell_nodes(c);
    if (static_cast<int>(nodes.size()) == grid.nodes_per_cell) {
      for (Index n : nodes) grid.connectivity.push_back(point_of_node(n));
      continue;
    }
    for (Index corner : model.mesh.cell(c)) {
      grid.connectivity.push_back(static_cast<Index>(grid.points.size()));
      grid.points.push_back(model.mesh.node(corner));
      point_dof_node.push_back(nodes[0]);
    }
  }

  io::Field disp{"displacement", 3, std::vector<double>(grid.points.size() * 3, 0.0)};
  for (std::size_t p = 0; p < grid.points.size(); ++p)
    for (int d = 0; d < dim_; ++d)
      disp.values[p * 3 + static_cast<std::size_t>(d)] =
          u[static_cast<std::size_t>(point_dof_node[p] * dim_ + d)];
  grid.point_data.push_back(std::move(disp));
  if (model.nonlocal) {
    io::Field alpha{"alpha", 1, {}};
    for (const Vec3& x : grid.points) alpha.values.push_back(model.nonlocal->alpha(x));
    grid.point_data.push_back(std::move(alpha));
  }

  // The stress of the damaged stiffness (THEORY §6) where the damage has grown.
  const fem::ConstitutiveField damaged =
      model.damage && !damage.history.empty()
          ? setup::damaged_stiffness(model.stiffness, *model.damage, damage.history)
          : fem::ConstitutiveField(0, 0, 0);
  const auto fields = assembly::cell_strain_stress(
      model.local_space(), damage.history.empty() ? model.stiffness : damaged, u, listed);
  const int nv = fem::voigt_size(dim_);
  io::Field strain{"strain", 9, {}}, stress{"stress", 9, {}}, region{"region", 1, {}},
      energy{"strain_energy_density", 1, {}};
  for (std::size_t k = 0; k < cells.size(); ++k) {  // the fields are in the order of `cells`
    const auto e = voigt_to_tensor(&fields.strain[k * static_cast<std::size_t>(nv)], dim_, true);
    const auto s = voigt_to_tensor(&fields.stress[k * static_cast<std::size_t>(nv)], dim_, false);
    strain.values.insert(strain.values.end(), e.begin(), e.end());
    stress.values.insert(stress.values.end(), s.begin(), s.end());
    region.values.push_back(model.mesh.cell_region[static_cast<std::size_t>(cells[k])]);
    energy.values.push_back(fields.energy_density[k]);
  }
  grid.cell_data = {std::move(strain), std::move(stress), std::move(region), std::move(energy)};
  if (model.nonlocal) {
    // α at the local quadrature points (cell mean) and the element kind:
    // 0 local/morphing (CG), 1 purely non-local CG, 2 DG, 3 DG degree 0.
    const auto& nl = *model.nonlocal;
    const std::size_t nq = model.rule.size();
    io::Field alpha_cell{"alpha_mean", 1, {}}, kind{"element_kind", 1, {}};
    for (Index c : cells) {
      double a = 0.0;
      for (std::size_t q = 0; q < nq; ++q)
        a += assembly::alpha_at_local_point(model.mesh, nl.alpha, c, model.rule[q].xi);
      alpha_cell.values.push_back(a / static_cast<double>(nq));
      const auto k = dm.continuity(c);
      kind.values.push_back(k == dofs::Continuity::discontinuous                    ? 2.0
                            : k == dofs::Continuity::discontinuous_constant         ? 3.0
                            : nl.morph.purely_nonlocal[static_cast<std::size_t>(c)] ? 1.0
                                                                                    : 0.0);
    }
    grid.cell_data.push_back(std::move(alpha_cell));
    grid.cell_data.push_back(std::move(kind));
  }
  auto cell_field = [&](const char* name, const std::vector<double>& values) {  // in the order of `cells`
    PERIMORPH_ASSERT(values.size() == cells.size(), "a cell field of another length than the cells written");
    grid.cell_data.push_back(io::Field{name, 1, values});
  };
  if (!fracture.damage.empty()) cell_field("damage", fracture.damage);
  if (!fracture.dissipated.empty()) cell_field("dissipated_energy", fracture.dissipated);
  if (!damage.mean.empty()) {
    cell_field("local_damage", damage.mean);
    cell_field("local_damage_max", damage.max);
    cell_field("damage_dissipated_energy", damage.dissipated);
  }
  if (selected) {
    // A piece: each cell's number in the whole mesh.
    io::Field number{"cell", 1, {}};
    for (Index c : cells) number.values.push_back(static_cast<double>(c));
    grid.cell_data.push_back(std::move(number));
  }
  return grid;
}

std::span<const Index> RunOutput::cells_written(const setup::Discretization& model) {
  const int processes = la::world_size();
  if (processes > 1 && piece_cells_.empty()) {
    const std::vector<char> mine = partition::cells_of_part(model.mesh, processes, la::world_rank());
    for (Index c = 0; c < model.mesh.num_cells(); ++c)
      if (mine[static_cast<std::size_t>(c)]) piece_cells_.push_back(c);
  }
  return piece_cells_;
}

void RunOutput::write_increment_vtu(const setup::Discretization& model, int increment, double load_factor,
                                    std::span<const double> u, const evolution::FractureFields& fracture,
                                    const evolution::DamageFields& damage, bool listed_by_row) {
  if (!vtu_) return;
  const int processes = la::world_size();
  if (processes == 1) {
    io::write_vtu(vtu_path(increment), increment_grid(model, u, fracture, damage, {}));
  } else {
    // Each process writes the cells of its part (the bisection of the
    // stretch pass), then process 0 the index. A failure anywhere removes
    // every process's piece.
    const std::span<const Index> cells = cells_written(model);
    const std::string stem = fmt::format("{}_{:04d}", basename_, increment);
    const std::string mine =
        (std::filesystem::path(directory_) / piece_name(stem, la::world_rank())).string();
    try {
      io::UnstructuredGrid piece;
      la::on_every_process([&] {
        piece = increment_grid(model, u, fracture, damage, cells);
        io::write_vtu(mine, piece);
      });
      la::on_process_zero([&] {
        std::vector<std::string> pieces;
        for (int r = 0; r < processes; ++r) pieces.push_back(piece_name(stem, r));
        io::write_pvtu(vtu_path(increment), piece, pieces);
      });
    } catch (...) {
      std::error_code ec;
      std::filesystem::remove(mine, ec);
      throw;
    }
  }
  la::on_process_zero([&] {
    const std::string name = std::filesystem::path(vtu_path(increment)).filename().string();
    if (listed_by_row)
      unlisted_ = io::PvdCollection::Entry{load_factor, name};
    else
      pvd_->add(load_factor, name);
  });
}

std::string RunOutput::piece_name(const std::string& stem, int process) {
  return fmt::format("{}_p{}.vtu", stem, process);
}

void RunOutput::remove_increment_files(const std::string& file) const {
  const std::filesystem::path path = std::filesystem::path(directory_) / file;
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (path.extension() == ".pvtu")
    for (int r = 0; r < la::world_size(); ++r)
      std::filesystem::remove(std::filesystem::path(directory_) / piece_name(path.stem().string(), r), ec);
}

void RunOutput::add_row(const IncrementRecord& r) {
  la::on_process_zero([&] {
    if (!csv_) return;
    std::vector<double> row{static_cast<double>(r.increment), r.load_factor};
    for (const Vec3& f : r.reactions)
      for (int d = 0; d < dim_; ++d) row.push_back(f[d]);
    row.insert(row.end(), {r.strain_energy, r.external_work, static_cast<double>(r.iterations),
                           r.relative_residual, r.wall_time});
    if (fracture_)
      row.insert(row.end(),
                 {r.dissipated, r.dissipated_increment, r.overshoot, r.released,
                  static_cast<double>(r.bonds_broken), static_cast<double>(r.bonds_broken_increment),
                  static_cast<double>(r.break_iterations), r.crack_area, r.broken_face_area,
                  static_cast<double>(r.floating_parts), static_cast<double>(r.cell_mechanisms)});
    if (damage_) {
      if (!fracture_) row.insert(row.end(), {r.overshoot, r.released});
      row.insert(row.end(),
                 {r.damage_dissipated, static_cast<double>(r.damage_iterations),
                  static_cast<double>(r.damage_newton_steps), static_cast<double>(r.damaged_points),
                  static_cast<double>(r.critical_points), r.max_damage});
    }
    if (adaptive_)
      row.insert(row.end(), {static_cast<double>(r.dofs), static_cast<double>(r.dg_cells),
                             static_cast<double>(r.nonlocal_cells), static_cast<double>(r.alpha_balls),
                             r.model_change, r.remodel_seconds});
    const auto unlisted = std::exchange(unlisted_, std::nullopt);
    auto remove_vtu = [&] {
      if (unlisted) remove_increment_files(unlisted->file);
    };
    try {
      csv_->add_row(row);
    } catch (const OutputError&) {
      remove_vtu();
      throw;
    }
    if (!unlisted) return;
    try {
      pvd_->add(unlisted->time, unlisted->file);
    } catch (const OutputError&) {
      csv_->remove_last_row();
      remove_vtu();
      throw;
    }
  });
}

void RunOutput::add_alpha_balls(std::span<const evolution::AlphaBall> balls) {
  la::on_process_zero([&] {
    if (!alpha_csv_) return;
    for (const auto& b : balls)
      alpha_csv_->add_row({static_cast<double>(b.increment), static_cast<double>(b.cell), b.center.x(),
                           b.center.y(), b.center.z(), b.radius, b.transition, b.predicted ? 1.0 : 0.0,
                           b.critical_damage ? 1.0 : 0.0});
  });
}

void RunOutput::add_failure_row(int increment, int iteration, std::size_t bonds,
                                const evolution::FailureEnergy& energy, double max_ratio,
                                const la::SolveReport& solve, double seconds) {
  la::on_process_zero([&] {
    if (!failures_csv_) return;
    failures_csv_->add_row({static_cast<double>(increment), static_cast<double>(iteration),
                            static_cast<double>(bonds), energy.dissipated, energy.overshoot, max_ratio,
                            static_cast<double>(solve.iterations), solve.rebuilt_preconditioner ? 1.0 : 0.0,
                            seconds});
  });
}

void RunOutput::add_failed_bonds(const setup::Discretization& model, int increment, int iteration,
                                 std::span<const assembly::StretchedBond> bonds, double s_crit) {
  la::on_process_zero([&] {
    if (!failed_bonds_csv_) return;
    const auto& pts = model.nonlocal->points;
    for (const auto& b : bonds) {
      const Vec3 xg = bonds::point_position(model.mesh, pts, b.id.e, b.id.g);
      const Vec3 xh = bonds::point_position(model.mesh, pts, b.id.f, b.id.h);
      const double critical = assembly::energy_at_stretch(b, s_crit);
      failed_bonds_csv_->add_row({static_cast<double>(increment), static_cast<double>(iteration), xg.x(),
                                  xg.y(), xg.z(), xh.x(), xh.y(), xh.z(), b.stretch, critical,
                                  b.energy - critical});
    }
  });
}

}  // namespace perimorph::run
