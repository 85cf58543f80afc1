#include "perimorph/run/run_output.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/io/grid.hpp"
#include "perimorph/io/pvtu_writer.hpp"
#include "perimorph/io/vtu_writer.hpp"
#include "perimorph/la/petsc_session.hpp"
#include "perimorph/setup/piece_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <utility>

namespace perimorph::run {

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

std::span<const Index> RunOutput::cells_written(const setup::Discretization& model) {
  const int processes = la::world_size();
  piece_cells_.clear();
  if (processes > 1) {
    const std::vector<char> mine = setup::cells_of_process(model, processes, la::world_rank());
    for (Index c = 0; c < model.mesh.num_cells(); ++c)
      if (mine[static_cast<std::size_t>(c)]) piece_cells_.push_back(c);
  }
  return piece_cells_;
}

void RunOutput::write_increment_vtu(const setup::Discretization& model, std::span<const Index> cells,
                                    int increment, double load_factor, std::span<const double> u,
                                    const evolution::FractureFields& fracture,
                                    const evolution::DamageFields& damage, bool listed_by_row) {
  if (!vtu_) return;
  const int processes = la::world_size();
  if (processes == 1) {
    io::write_vtu(vtu_path(increment), increment_grid(model, u, fracture, damage, {}));
  } else {
    // Each process writes the cells of its part (the bisection of the
    // stretch pass), then process 0 the index. A failure anywhere removes
    // every process's piece.
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

void RunOutput::add_failed_bonds(int increment, int iteration, std::span<const assembly::StretchedBond> bonds,
                                 std::span<const evolution::BondPoints> points, double s_crit) {
  PERIMORPH_ASSERT(points.size() == bonds.size(), "a position for each failed bond");
  la::on_process_zero([&] {
    if (!failed_bonds_csv_) return;
    for (std::size_t k = 0; k < bonds.size(); ++k) {
      const auto& b = bonds[k];
      const Vec3 &xg = points[k].g, &xh = points[k].h;
      const double critical = assembly::energy_at_stretch(b, s_crit);
      failed_bonds_csv_->add_row({static_cast<double>(increment), static_cast<double>(iteration), xg.x(),
                                  xg.y(), xg.z(), xh.x(), xh.y(), xh.z(), b.stretch, critical,
                                  b.energy - critical});
    }
  });
}

}  // namespace perimorph::run
