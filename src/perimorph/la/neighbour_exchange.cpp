#include "perimorph/la/neighbour_exchange.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <petscsys.h>

#include <algorithm>
#include <limits>

namespace perimorph::la {

namespace {

constexpr PetscMPIInt kExchangeTag = 7917;  ///< the lists' messages (the counts go on PETSc's own)

void check_mpi(int code, const char* what) {
  if (code != MPI_SUCCESS) throw SolverError(std::string(what) + " failed");
}

}  // namespace

std::vector<double>& parcel_for(std::vector<Parcel>& parcels, int process) {
  auto it =
      std::find_if(parcels.begin(), parcels.end(), [&](const Parcel& p) { return p.process == process; });
  if (it == parcels.end()) it = parcels.insert(parcels.end(), Parcel{process, {}});
  return it->values;
}

int hashed_process(std::initializer_list<std::int64_t> key, int processes) {
  std::uint64_t h = 0x9E3779B97F4A7C15ULL;
  for (std::int64_t k : key) {  // splitmix64's finalizer over each part
    h ^= static_cast<std::uint64_t>(k) + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBULL;
    h ^= h >> 31;
  }
  return static_cast<int>(h % static_cast<std::uint64_t>(processes));
}

std::vector<Parcel> exchange(const std::vector<Parcel>& outgoing) {
  std::vector<Parcel> incoming;
  const int size = world_size(), rank = world_rank();
  std::vector<PetscMPIInt> to, counts;
  for (const Parcel& p : outgoing) {
    PERIMORPH_ASSERT(p.process >= 0 && p.process < size && p.process != rank,
                     "exchange: a parcel for this process or none");
    PERIMORPH_ASSERT(p.values.size() < static_cast<std::size_t>(std::numeric_limits<PetscMPIInt>::max()),
                     "exchange: a parcel too large for one message");
    if (p.values.empty()) continue;
    to.push_back(p.process);
    counts.push_back(static_cast<PetscMPIInt>(p.values.size()));
  }
  if (size == 1) return incoming;
  for (std::size_t k = 1; k < to.size(); ++k)
    PERIMORPH_ASSERT(std::find(to.begin(), to.begin() + static_cast<std::ptrdiff_t>(k), to[k]) ==
                         to.begin() + static_cast<std::ptrdiff_t>(k),
                     "exchange: two parcels for one process");

  // Who sends this process how much: PETSc's sparse consensus.
  PetscMPIInt nfrom = 0;
  PetscMPIInt* from = nullptr;
  PetscMPIInt* from_counts = nullptr;
  PM_PETSC(PetscCommBuildTwoSided(PETSC_COMM_WORLD, 1, MPI_INT, static_cast<PetscMPIInt>(to.size()),
                                  to.data(), counts.data(), &nfrom, &from, &from_counts));
  std::vector<std::pair<PetscMPIInt, PetscMPIInt>> senders;
  for (PetscMPIInt k = 0; k < nfrom; ++k) senders.emplace_back(from[k], from_counts[k]);
  PetscFree(from);
  PetscFree(from_counts);
  std::sort(senders.begin(), senders.end());

  std::vector<MPI_Request> requests;
  requests.reserve(senders.size() + to.size());
  incoming.resize(senders.size());
  for (std::size_t k = 0; k < senders.size(); ++k) {
    incoming[k].process = senders[k].first;
    incoming[k].values.resize(static_cast<std::size_t>(senders[k].second));
    requests.emplace_back();
    check_mpi(MPI_Irecv(incoming[k].values.data(), senders[k].second, MPI_DOUBLE, senders[k].first,
                        kExchangeTag, PETSC_COMM_WORLD, &requests.back()),
              "MPI_Irecv");
  }
  for (const Parcel& p : outgoing) {
    if (p.values.empty()) continue;
    requests.emplace_back();
    check_mpi(MPI_Isend(p.values.data(), static_cast<int>(p.values.size()), MPI_DOUBLE, p.process,
                        kExchangeTag, PETSC_COMM_WORLD, &requests.back()),
              "MPI_Isend");
  }
  check_mpi(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
            "MPI_Waitall");
  return incoming;
}

std::vector<double> gather_on_process_zero(const std::vector<double>& mine) {
  const int size = world_size();
  if (size == 1) return mine;
  const int count = static_cast<int>(mine.size());
  const bool zero = world_rank() == 0;
  std::vector<int> counts(zero ? static_cast<std::size_t>(size) : 0U), offsets(counts.size() + 1, 0);
  check_mpi(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD), "MPI_Gather");
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(static_cast<std::size_t>(offsets.back()));
  check_mpi(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                        0, PETSC_COMM_WORLD),
            "MPI_Gatherv");
  return all;
}

std::vector<double> gather_onto(const std::vector<double>& mine, Onto onto) {
  return onto == Onto::every_process ? all_gather(mine) : gather_on_process_zero(mine);
}

bool receives(Onto onto) {
  return onto == Onto::every_process || world_rank() == 0;
}

double largest_over_processes(double value) {
  if (world_size() == 1) return value;
  double out = value;
  check_mpi(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD), "MPI_Allreduce");
  return out;
}

}  // namespace perimorph::la
