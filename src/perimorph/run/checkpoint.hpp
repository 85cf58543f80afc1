#pragma once
// Checkpoints of a quasi-static run (docs/output.md, "Restart"): one file,
// BASENAME.checkpoint in the output directory, written atomically
// (io::AtomicFile) after every [output] checkpoint_every increments and when
// SIGINT/SIGTERM stops the run between increments. It holds, bit for bit,
// what the next increment starts from: the run state (u, load, α, failed
// bonds, damage history, energy ledger), each evolution component's own
// bookkeeping, the constrained system (K, A and the right-hand side with
// every downdate and spring in them), the position of every output file and
// the case's values. `perimorph run CASE --restart PATH` continues it
// (QuasiStaticRun): the continued run's CSV rows and VTU files are those of
// an uninterrupted run, bit for bit, as long as the solver's result does not
// depend on its history (a direct solve, or a Krylov solve whose
// preconditioner is rebuilt with each operator; a preconditioner kept across
// solves, -ksp_reuse_preconditioner, is rebuilt on restart, which changes
// the solutions within the solver's tolerance).
//
// Layout: "perimorph-checkpoint" tag, format version, the case's values
// (casefile/case_values.hpp), then the run's sections, each opened by a tag
// (core::BinaryWriter::tag) so that a reader out of step stops with a message.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/core/binary_stream.hpp"
#include "perimorph/core/mapped_file.hpp"

#include <cstdint>
#include <string>

namespace perimorph::run {

/// Bumped whenever the layout changes: an older checkpoint is refused, not
/// misread.
inline constexpr std::uint32_t kCheckpointVersion = 3;

/// DIRECTORY/BASENAME.checkpoint.
std::string checkpoint_path(const std::string& directory, const std::string& basename);

/// The checkpoint `--restart` names: `given` itself if it is a file, else
/// given/BASENAME.checkpoint. Throws InputError if there is none.
std::string find_checkpoint(const std::string& given, const std::string& basename);

/// The file, mapped (core::MappedFile: a process touches only what it reads;
/// throws Error naming it).
core::MappedFile read_checkpoint_file(const std::string& path);

/// The opening: tag, version, the case's values ([output] checkpoint_every
/// left out: it may change between the runs).
void write_header(core::BinaryWriter& out, const casefile::CaseConfig& config);
/// Checks the opening against this build and `config`: throws InputError
/// naming the checkpoint and every case key whose value differs.
void check_header(core::BinaryReader& in, const casefile::CaseConfig& config);

}  // namespace perimorph::run
