#pragma once
// What a run writes: a VTU per output increment collected in a PVD, and one
// CSV row per increment (THEORY-independent bookkeeping; format in
// docs/output.md).

#include "perimorph/assembly/bond_stretch.hpp"
#include "perimorph/evolution/adaptivity.hpp"
#include "perimorph/evolution/bond_failure.hpp"
#include "perimorph/evolution/local_damage.hpp"
#include "perimorph/io/csv_table.hpp"
#include "perimorph/io/grid.hpp"
#include "perimorph/io/output_lock.hpp"
#include "perimorph/io/pvd_writer.hpp"
#include "perimorph/la/linear_solver.hpp"
#include "perimorph/setup/discretization.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace perimorph::run {

struct IncrementRecord {
  int increment = 0;
  double load_factor = 0.0;
  std::vector<Vec3> reactions;  ///< one per reaction set
  double strain_energy = 0.0;
  double external_work = 0.0;
  int iterations = 0;
  double relative_residual = 0.0;
  double wall_time = 0.0;  ///< seconds since the start of the run
  // Fracture runs only (THEORY §5):
  double dissipated = 0.0;            ///< D: every failed bond's energy at s_crit, cumulative (THEORY §5)
  double dissipated_increment = 0.0;  ///< the part of D from this increment
  double overshoot = 0.0;             ///< energy the failed bonds held beyond s_crit, cumulative
  double released = 0.0;         ///< W − U − D − overshoot: released by re-equilibration after failures
  std::size_t bonds_broken = 0;  ///< failed bonds, cumulative (pre-crack cuts not counted)
  std::size_t bonds_broken_increment = 0;
  int break_iterations = 0;         ///< solves after the first one in this increment
  double crack_area = 0.0;          ///< evolution::BondFailure::crack_area().projected
  double broken_face_area = 0.0;    ///< evolution::BondFailure::crack_area().total
  std::size_t floating_parts = 0;   ///< parts cut free and held by a minimal support, cumulative
  std::size_t cell_mechanisms = 0;  ///< cells with a motion no intact bond resists, held, cumulative
  // Adaptive runs only ([adaptivity], THEORY §5):
  Index dofs = 0;                ///< of the model the increment ended on
  Index dg_cells = 0;            ///< cells with private (DG) nodes
  Index nonlocal_cells = 0;      ///< cells with α > 0 at a non-local point
  std::size_t alpha_balls = 0;   ///< balls added to α, cumulative
  double model_change = 0.0;     ///< EnergyLedger::model_change, cumulative
  double remodel_seconds = 0.0;  ///< rebuilding the discretization and the system, cumulative
  // Runs with [material.damage] only (THEORY §6):
  double damage_dissipated = 0.0;   ///< EnergyLedger::damage_dissipated, cumulative
  int damage_iterations = 0;        ///< damage updates (fixed-point iterations) in this increment
  int damage_newton_steps = 0;      ///< Newton steps of [damage] solver = "newton" in this increment
  std::size_t damaged_points = 0;   ///< local quadrature points with d > 0
  std::size_t critical_points = 0;  ///< local quadrature points with d = d_c
  double max_damage = 0.0;          ///< largest d
};

/// How far a run's output had got (a checkpoint, run/checkpoint.hpp): the
/// rows of each table and the PVD's entries.
struct OutputPosition {
  std::size_t rows = 0, alpha_rows = 0, failure_rows = 0, failed_bond_rows = 0;
  std::vector<io::PvdCollection::Entry> pvd;
};

class RunOutput {
 public:
  /// Creates `directory` (and parents). Files: BASENAME.csv, BASENAME.pvd,
  /// BASENAME_NNNN.vtu. With `resume`, continues the files there after that
  /// position (later rows are cut off; io::CsvTable) instead of starting them.
  /// On more than one MPI process, process 0 writes everything (each holds
  /// the whole state) and the others' RunOutput writes nothing; each call
  /// (but write_increment_vtu) is collective (la::on_process_zero), so that
  /// an error of process 0 stops every process at the same point.
  RunOutput(const setup::Discretization& model, std::string directory, std::string basename,
            std::vector<std::string> reaction_names, const OutputPosition* resume = nullptr);
  OutputPosition position() const;

  /// Writes the increment's VTU and lists it in the PVD; with `listed_by_row`
  /// the PVD entry waits for add_row (below). On P > 1 processes collective:
  /// each process writes `cells`, those of its part (cells_written), as
  /// BASENAME_NNNN_pR.vtu, with a cell array `cell` (the cell's number in the
  /// whole mesh), and process 0 the index BASENAME_NNNN.pvtu listed in the
  /// PVD (issue 17, item 3); an error on any process stops every process
  /// (la::on_every_process) and leaves no piece of that increment.
  void write_increment_vtu(const setup::Discretization& model, std::span<const Index> cells, int increment,
                           double load_factor, std::span<const double> u,
                           const evolution::FractureFields& fracture = {},
                           const evolution::DamageFields& damage = {}, bool listed_by_row = false);
  /// The increment's CSV row, then the PVD entry of a VTU written with
  /// listed_by_row: in this order (after the VTU file) the files stay in step
  /// whatever fails — a failed row removes that VTU, a failed entry also the
  /// row (cutting and deleting need no space on a full disk) — and
  /// OutputError names the file and the system's reason.
  void add_row(const IncrementRecord& r);
  /// Fracture runs: one row per bond-breaking iteration in BASENAME_failures.csv
  /// (increment, iteration, bonds failed, their energy at s_crit and beyond,
  /// the largest s/s_crit, Krylov iterations of the re-solve, whether its
  /// preconditioner was rebuilt, and the iteration's wall time `seconds`:
  /// stretch pass, update of the system and re-solve).
  void add_failure_row(int increment, int iteration, std::size_t bonds,
                       const evolution::FailureEnergy& energy, double max_ratio, const la::SolveReport& solve,
                       double seconds);
  /// With [output] failed_bonds: one row per bond of `bonds` in
  /// BASENAME_failed_bonds.csv (its points, stretch, energy at s_crit and
  /// beyond; docs/output.md), `points` where each bond's are
  /// (BondFailure::proposed_points). Bonds already failed are the caller's to skip.
  void add_failed_bonds(int increment, int iteration, std::span<const assembly::StretchedBond> bonds,
                        std::span<const evolution::BondPoints> points, double s_crit);

  /// Adaptive runs: one row per ball added to α in BASENAME_alpha.csv.
  void add_alpha_balls(std::span<const evolution::AlphaBall> balls);

  const std::string& directory() const { return directory_; }
  std::string csv_path() const;
  std::string pvd_path() const;
  /// The VTU of an increment (written or not: [output] vtu may be false);
  /// on several processes its .pvtu index.
  std::string vtu_path(int increment) const;
  /// BASENAME_failures.csv ("" for a run without [fracture]).
  std::string failures_csv_path() const;
  /// [output] vtu (the same on every process).
  bool writes_vtu() const { return vtu_; }
  /// The cells this process writes in an increment's VTU, ascending: on P > 1
  /// processes those of its part (partition::cells_of_part), on one empty
  /// (every cell). The fields passed to write_increment_vtu are theirs, in
  /// this order. Found anew for each model (a piece rebuilt for a grown α
  /// numbers its cells anew); valid until the next call.
  std::span<const Index> cells_written(const setup::Discretization& model);

 private:
  std::string directory_, basename_;
  int dim_;
  bool fracture_ = false, adaptive_ = false, damage_ = false, vtu_ = false;
  std::unique_ptr<io::OutputLock> lock_;  ///< taken before any file is touched
  std::unique_ptr<io::CsvTable> csv_, failures_csv_, failed_bonds_csv_, alpha_csv_;
  /// A VTU written with listed_by_row, waiting for its row: time and file name.
  std::optional<io::PvdCollection::Entry> unlisted_;
  std::unique_ptr<io::PvdCollection> pvd_;
  /// This process's cells in a distributed run's VTU pieces (cells_written).
  std::vector<Index> piece_cells_;

  /// The increment's grid: every cell, or the cells `listed` (ascending),
  /// the points they use and a cell field `cell` (their numbers in the whole
  /// mesh); the fracture and damage fields are those of the cells written.
  io::UnstructuredGrid increment_grid(const setup::Discretization& model, std::span<const double> u,
                                      const evolution::FractureFields& fracture,
                                      const evolution::DamageFields& damage,
                                      std::span<const Index> listed) const;
  /// The VTU piece of process `process` of the increment file STEM.pvtu.
  static std::string piece_name(const std::string& stem, int process);
  /// Removes an increment's VTU, or its .pvtu and every process's piece.
  void remove_increment_files(const std::string& file) const;
};

}  // namespace perimorph::run
