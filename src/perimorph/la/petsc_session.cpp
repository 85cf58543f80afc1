#include "perimorph/la/petsc_session.hpp"

#include "perimorph/core/types.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscsys.h>

#include <cctype>
#include <iterator>
#include <sstream>
#include <type_traits>
#include <vector>

static_assert(std::is_same_v<PetscInt, perimorph::Index>, "perimorph::Index must match PetscInt");
static_assert(std::is_same_v<PetscScalar, double>, "perimorph needs a real, double-precision PETSc");

namespace perimorph::la {

PetscSession::PetscSession(int& argc, char**& argv) {
  PM_PETSC(PetscInitialize(&argc, &argv, nullptr, nullptr));
}

PetscSession::PetscSession() {
  PM_PETSC(PetscInitializeNoArguments());
}

PetscSession::~PetscSession() {
  PetscFinalize();
}

void add_options(const std::string& options) {
  // Insert option by option, skipping those already given (command line wins).
  std::istringstream in(options);
  std::vector<std::string> words{std::istream_iterator<std::string>(in),
                                 std::istream_iterator<std::string>()};
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& name = words[i];
    if (name.size() < 2 || name[0] != '-')
      throw InputError(fmt::format("PETSc options must start with '-': got '{}' in \"{}\"", name, options));
    std::string value;
    if (i + 1 < words.size() && !(words[i + 1][0] == '-' && words[i + 1].size() > 1 &&
                                  std::isalpha(static_cast<unsigned char>(words[i + 1][1]))))
      value = words[++i];
    PetscBool set = PETSC_FALSE;
    PM_PETSC(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
    if (set) continue;
    PM_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
  }
}

std::vector<std::string> unused_options() {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  PM_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::string> out;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i];
    if (name == "options_left") continue;
    out.push_back(values[i] != nullptr ? fmt::format("-{} {}", name, values[i]) : "-" + name);
  }
  PM_PETSC(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  return out;
}

int world_size() {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

int world_rank() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

void barrier() {
  MPI_Barrier(PETSC_COMM_WORLD);
}

void set_option(const std::string& name, const std::string& value) {
  if (name.size() < 2 || name[0] != '-')
    throw InputError(fmt::format("PETSc option names must start with '-': got '{}'", name));
  PM_PETSC(PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str()));
}

void clear_option(const std::string& name) {
  if (name.size() < 2 || name[0] != '-')
    throw InputError(fmt::format("PETSc option names must start with '-': got '{}'", name));
  PM_PETSC(PetscOptionsClearValue(nullptr, name.c_str()));
}

}  // namespace perimorph::la
