#include "perimorph/la/key_exchange.hpp"

#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/petsc_session.hpp"

#include <petscsf.h>

#include <fmt/format.h>

namespace perimorph::la {

std::vector<Index> values_of_keys(std::span<const Index> keys, std::span<const Index> values,
                                  std::span<const Index> wanted, Index key_space) {
  static_assert(sizeof(Index) == sizeof(PetscInt), "Index must match PetscInt");
  PERIMORPH_ASSERT(keys.size() == values.size(), "values_of_keys takes a value for every key");
  for (std::span<const Index> s : {keys, wanted})
    for (Index k : s)
      PERIMORPH_ASSERT(k >= 0 && k < key_space, "values_of_keys: a key outside the key space");
  for (Index v : values) PERIMORPH_ASSERT(v >= 0, "values_of_keys takes values of 0 or more");
  std::vector<Index> out(wanted.size(), -1);

  // The key space cut into one range per process (PetscLayout): each key's
  // broker. The holders send their keys' values and a count to the brokers
  // (a reduction over a star forest from the held keys to the layout), the
  // brokers to the askers (a broadcast over one from the asked keys).
  PetscLayout layout = nullptr;
  PM_PETSC(PetscLayoutCreate(PETSC_COMM_WORLD, &layout));
  PM_PETSC(PetscLayoutSetSize(layout, key_space));
  PM_PETSC(PetscLayoutSetBlockSize(layout, 1));
  PM_PETSC(PetscLayoutSetUp(layout));
  PetscInt brokered = 0;
  PM_PETSC(PetscLayoutGetLocalSize(layout, &brokered));
  std::vector<Index> at_broker(static_cast<std::size_t>(brokered), -1), holders(at_broker.size(), 0);
  const std::vector<Index> ones(keys.size(), 1);
  PetscSF held = nullptr, asked = nullptr;
  PetscErrorCode e = PetscSFCreate(PETSC_COMM_WORLD, &held);
  if (!e)
    e = PetscSFSetGraphLayout(held, layout, static_cast<PetscInt>(keys.size()), nullptr, PETSC_COPY_VALUES,
                              keys.data());
  if (!e) e = PetscSFReduceBegin(held, MPIU_INT, values.data(), at_broker.data(), MPI_REPLACE);
  if (!e) e = PetscSFReduceEnd(held, MPIU_INT, values.data(), at_broker.data(), MPI_REPLACE);
  if (!e) e = PetscSFReduceBegin(held, MPIU_INT, ones.data(), holders.data(), MPI_SUM);
  if (!e) e = PetscSFReduceEnd(held, MPIU_INT, ones.data(), holders.data(), MPI_SUM);
  if (!e) e = PetscSFCreate(PETSC_COMM_WORLD, &asked);
  if (!e)
    e = PetscSFSetGraphLayout(asked, layout, static_cast<PetscInt>(wanted.size()), nullptr, PETSC_COPY_VALUES,
                              wanted.data());
  if (!e) e = PetscSFBcastBegin(asked, MPIU_INT, at_broker.data(), out.data(), MPI_REPLACE);
  if (!e) e = PetscSFBcastEnd(asked, MPIU_INT, at_broker.data(), out.data(), MPI_REPLACE);
  PetscSFDestroy(&held);
  PetscSFDestroy(&asked);
  PetscLayoutDestroy(&layout);
  PM_PETSC(e);
  for (Index h : holders) PERIMORPH_ASSERT(h <= 1, "values_of_keys: a key held by two processes");

  // Every process learns whether any key was missing, so that all throw.
  Index missing = -1;
  for (std::size_t k = 0; k < out.size() && missing < 0; ++k)
    if (out[k] < 0) missing = wanted[k];
  const int any = max_over_processes(missing >= 0 ? 1 : 0);
  if (missing >= 0) throw Error(fmt::format("values_of_keys: no process holds key {}", missing));
  if (any) throw Error("values_of_keys: another process asked for a key no process holds");
  return out;
}

Index offset_over_processes(Index count) {
  if (world_size() == 1) return 0;
  PetscInt mine = count, before = 0;
  if (MPI_Exscan(&mine, &before, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD) != MPI_SUCCESS)
    throw SolverError("MPI_Exscan failed");
  return world_rank() == 0 ? 0 : before;
}

}  // namespace perimorph::la
