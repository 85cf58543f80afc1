#include "perimorph/la/petsc_session.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/core/types.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscsys.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iterator>
#include <sstream>
#include <type_traits>
#include <vector>

// An AddressSanitizer build (PERIMORPH_SANITIZE, docs/sanitizers.md): LeakSanitizer's interface.
#if defined(__SANITIZE_ADDRESS__)
#define PERIMORPH_LEAK_CHECK 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PERIMORPH_LEAK_CHECK 1
#endif
#endif
#ifdef PERIMORPH_LEAK_CHECK
#include <sanitizer/lsan_interface.h>
#endif

static_assert(std::is_same_v<PetscInt, perimorph::Index>, "perimorph::Index must match PetscInt");
static_assert(std::is_same_v<PetscScalar, double>, "perimorph needs a real, double-precision PETSc");

namespace perimorph::la {

namespace {

// In an AddressSanitizer build, what this thread allocates while the object
// lives is no leak to LeakSanitizer: OpenMPI's MPI_Init (run by
// PetscInitialize) keeps allocations it never frees, some made by components
// it unloads again, whose stacks no suppression can name. No perimorph code
// runs inside. Elsewhere it does nothing.
struct NotLeakChecked {
  NotLeakChecked() {
#ifdef PERIMORPH_LEAK_CHECK
    __lsan_disable();
#endif
  }
  ~NotLeakChecked() {
#ifdef PERIMORPH_LEAK_CHECK
    __lsan_enable();
#endif
  }
  NotLeakChecked(const NotLeakChecked&) = delete;
  NotLeakChecked& operator=(const NotLeakChecked&) = delete;
};

}  // namespace

PetscSession::PetscSession(int& argc, char**& argv) {
  [[maybe_unused]] const NotLeakChecked not_checked;
  PM_PETSC(PetscInitialize(&argc, &argv, nullptr, nullptr));
}

PetscSession::PetscSession() {
  [[maybe_unused]] const NotLeakChecked not_checked;
  PM_PETSC(PetscInitializeNoArguments());
}

PetscSession::~PetscSession() {
#ifdef PERIMORPH_LEAK_CHECK
  // The leak check runs here, while MPI is still up, and not again at exit. What
  // OpenMPI allocates at MPI_Init is still reachable now; MPI_Finalize leaves it
  // behind and unloads (dlclose) the components that allocated it, and the
  // reports at exit then show stacks of "<unknown module>" that no suppression
  // can name. Everything perimorph allocated since PetscInitialize is checked.
  __lsan_do_leak_check();
#endif
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

namespace {

bool petsc_running() {
  PetscBool running = PETSC_FALSE;
  PetscInitialized(&running);
  return running == PETSC_TRUE;
}

}  // namespace

int world_size() {
  PetscMPIInt size = 1;
  if (petsc_running()) MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

void abort_every_process(int status) {
  std::fflush(stdout);
  std::fflush(stderr);
  MPI_Abort(PETSC_COMM_WORLD, status);
  std::abort();  // MPI_Abort does not return
}

int world_rank() {
  PetscMPIInt rank = 0;
  if (petsc_running()) MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

std::vector<double> all_gather(const std::vector<double>& mine) {
  const int size = world_size();
  if (size == 1) return mine;
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size) + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> all(static_cast<std::size_t>(offsets.back()));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                 PETSC_COMM_WORLD);
  return all;
}

void barrier() {
  MPI_Barrier(PETSC_COMM_WORLD);
}

int max_over_processes(int value) {
  if (world_size() == 1) return value;
  int out = value;
  MPI_Allreduce(&value, &out, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  return out;
}

std::vector<double> sum_over_processes(std::vector<double> values) {
  if (world_size() == 1 || values.empty()) return values;
  const std::vector<double> all = all_gather(values);
  const std::size_t n = values.size();
  for (std::size_t i = 0; i < n; ++i) {
    double sum = all[i];
    for (std::size_t at = n + i; at < all.size(); at += n) sum += all[at];
    values[i] = sum;
  }
  return values;
}

std::vector<double> from_owners(std::vector<double> values) {
  if (world_size() == 1 || values.empty()) return values;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                PETSC_COMM_WORLD);
  return values;
}

std::vector<char> union_over_processes(std::vector<char> flags) {
  if (world_size() == 1 || flags.empty()) return flags;
  std::vector<double> set;
  for (std::size_t k = 0; k < flags.size(); ++k) {
    PERIMORPH_ASSERT(flags[k] == 0 || flags[k] == 1, "union_over_processes takes flags of 0 and 1");
    if (flags[k]) set.push_back(static_cast<double>(k));
  }
  for (double k : all_gather(set)) flags[static_cast<std::size_t>(k)] = 1;
  return flags;
}

bool any_over_processes(bool holds) {
  return min_over_processes({holds ? -1LL : 0LL}).front() < 0;
}

std::vector<long long> min_over_processes(std::vector<long long> values) {
  if (world_size() == 1 || values.empty()) return values;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_LONG_LONG, MPI_MIN,
                PETSC_COMM_WORLD);
  return values;
}

void on_process_zero(const std::function<void()>& act) {
  // Process 0 is then the lowest (and only) process that can fail.
  on_every_process([&] {
    if (world_rank() == 0) act();
  });
}

void on_every_process(const std::function<void()>& act) {
  if (world_size() == 1) {
    act();
    return;
  }
  std::exception_ptr error;
  int kind = 0;  // 1: an output error, 2: any other
  std::string message;
  try {
    act();
  } catch (const OutputError& e) {
    error = std::current_exception();
    kind = 1;
    message = e.what();
  } catch (const std::exception& e) {
    error = std::current_exception();
    kind = 2;
    message = e.what();
  } catch (...) {
    error = std::current_exception();
    kind = 2;
    message = "unknown error";
  }
  const int size = world_size(), rank = world_rank();
  const int mine = error ? rank : size;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (first == size) return;
  // The lowest failing process tells every other what it met.
  int length = static_cast<int>(message.size());
  MPI_Bcast(&kind, 1, MPI_INT, first, PETSC_COMM_WORLD);
  MPI_Bcast(&length, 1, MPI_INT, first, PETSC_COMM_WORLD);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, PETSC_COMM_WORLD);
  if (rank != 0) throw StoppedByProcessZero(kind == 1);
  if (first == 0) std::rethrow_exception(error);
  const std::string reported = fmt::format("process {}: {}", first, message);
  if (kind == 1) throw OutputError(reported);
  throw Error(reported);
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
