#pragma once
// RAII for PetscInitialize/PetscFinalize. Command-line options after the
// program's own are handed to PETSc's options database; add_options() inserts
// a string of options (e.g. a case file's [solver] petsc_options) with lower
// precedence than the command line.

#include <functional>
#include <string>
#include <vector>

namespace perimorph::la {

class PetscSession {
 public:
  PetscSession(int& argc, char**& argv);
  PetscSession();
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
};

/// Inserts options ("-ksp_type cg -pc_type gamg") into PETSc's database. Options
/// already set (from the command line) keep their value. Throws InputError with
/// PETSc's message if the string cannot be parsed.
void add_options(const std::string& options);

/// The options in PETSc's database that nothing has read so far, each as
/// "-name" or "-name value", in PETSc's order. Call it after the solver has
/// read its options (after the first solve: preconditioner set-up reads some)
/// to find misspelt options and options of a solver not in use. `-options_left`
/// is left out: PETSc reads it at PetscFinalize and reports on its own.
std::vector<std::string> unused_options();

/// Every process's `mine`, one after the other in rank order, on every
/// process (collective; `mine` itself on one rank).
std::vector<double> all_gather(const std::vector<double>& mine);

/// Number of MPI ranks in PETSC_COMM_WORLD (1 without a PETSc session, e.g.
/// in `perimorph check`).
int world_size();
/// This process's rank in PETSC_COMM_WORLD (0 without a PETSc session).
int world_rank();
/// Waits until every rank of PETSC_COMM_WORLD has reached it.
void barrier();
/// Stops every rank of PETSC_COMM_WORLD at once with exit status `status`
/// (MPI_Abort): for a failure met by one rank while the others may be
/// waiting for it in a collective call (the MPI tests' harness).
[[noreturn]] void abort_every_process(int status);
/// The largest of `value` over the ranks of PETSC_COMM_WORLD (collective;
/// `value` itself on one rank).
int max_over_processes(int value);
/// The elementwise sum of `values` over the ranks, added in rank order on
/// every process (each gets the same bits, whatever MPI's reduction
/// algorithm; collective, the same length on every rank; `values` itself on
/// one rank).
std::vector<double> sum_over_processes(std::vector<double> values);
/// Each entry from the one process that holds it, the others passing −0.0
/// there: one MPI sum, exact whatever order MPI adds in (x + (−0) = x, signed
/// zeros and NaN included). Collective, the same length on every rank;
/// `values` itself on one rank.
std::vector<double> from_owners(std::vector<double> values);
/// The elementwise smallest of `values` over the ranks (collective; every
/// rank passes the same length; `values` itself on one rank).
std::vector<long long> min_over_processes(std::vector<long long> values);
/// Whether `holds` is true on any rank (collective; `holds` itself on one rank).
bool any_over_processes(bool holds);
/// The elementwise largest of `flags` (0 or 1: their union) over the ranks,
/// sending only where they are set: each rank's set entries are gathered by
/// every rank (8 bytes a set entry), not the whole array (collective; the
/// same length on every rank; `flags` itself on one rank).
std::vector<char> union_over_processes(std::vector<char> flags);

/// Runs `act` on process 0 alone (what it alone does in a run every process
/// computes: writing the output) and lets every process know how it ended
/// (collective): an exception it throws is rethrown on process 0 and, as
/// StoppedByProcessZero, on the others, so that every process stops at the
/// same point and process 0 alone reports why (issue 17, item 3). On one
/// process, `act()`.
void on_process_zero(const std::function<void()>& act);

/// Runs `act` on every process (each its own share of the output: its VTU
/// piece) and lets every process know how it ended (collective). If it threw
/// on any process, the error of the lowest such process is the one reported:
/// process 0 throws it (its own exception, or an OutputError/Error with that
/// process's message, prefixed "process R: "), every other process throws
/// StoppedByProcessZero, so that the error reaches the user once (issue 17,
/// item 3). On one process, `act()`.
void on_every_process(const std::function<void()>& act);

/// Sets one option ("-ksp_type", "preonly"), replacing any value it had, the
/// command line's included; an empty value sets a flag. For programs that
/// change solvers between runs (benchmarks); case files use add_options.
void set_option(const std::string& name, const std::string& value = "");

/// Removes one option from PETSc's database; nothing happens if it is not set.
void clear_option(const std::string& name);

}  // namespace perimorph::la
