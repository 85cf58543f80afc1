#pragma once
// Point-to-point exchanges between the processes that share something (issue
// 17, item 2): each process sends a list of values to the few processes that
// need them, and no process receives what it has no use for. The processes a
// process hears from are found with PETSc's PetscCommBuildTwoSided (a
// non-blocking consensus: no P × P table of counts), then the lists travel
// directly. And a gather onto process 0 alone, for what only it writes.

#include <cstdint>
#include <initializer_list>
#include <vector>

namespace perimorph::la {

/// A list of values to or from one process.
struct Parcel {
  int process = 0;
  std::vector<double> values;
};

/// The values of the parcel for `process` in `parcels`, a new parcel if it has none.
std::vector<double>& parcel_for(std::vector<Parcel>& parcels, int process);

/// A process chosen by a hash of `key` (a few whole numbers), the same on
/// every process: the one that handles a thing several processes may hold,
/// spreading such things evenly over the processes.
int hashed_process(std::initializer_list<std::int64_t> key, int processes);

/// Sends each parcel of `outgoing` to its process (distinct processes, none
/// this one; an empty parcel is not sent) and returns the parcels the other
/// processes sent this one, ordered by sender (collective over
/// PETSC_COMM_WORLD; nothing on one process).
std::vector<Parcel> exchange(const std::vector<Parcel>& outgoing);

/// Every process's `mine`, one after the other in rank order, on process 0;
/// empty on the others (collective; `mine` itself on one process).
std::vector<double> gather_on_process_zero(const std::vector<double>& mine);

/// Where a gathered whole goes: to every process, or to process 0 alone (what
/// only it writes, as a checkpoint: the others then hold nothing whole).
enum class Onto { every_process, process_zero };

/// Every process's `mine`, one after the other in rank order, onto `onto`
/// (la::all_gather or gather_on_process_zero; collective).
std::vector<double> gather_onto(const std::vector<double>& mine, Onto onto);

/// Whether this process receives what is gathered onto `onto`.
bool receives(Onto onto);

/// The largest of `value` over the processes (collective; exact).
double largest_over_processes(double value);

}  // namespace perimorph::la
