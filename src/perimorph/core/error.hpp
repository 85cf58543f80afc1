#pragma once
// Two kinds of errors (STYLE.md habit 8):
//  - broken internal invariants: PERIMORPH_ASSERT (active in every build; the
//    cost is negligible next to assembly and it keeps release runs honest);
//  - errors a user can act on: exceptions derived from perimorph::Error, thrown
//    with a message naming what was wrong and what is allowed; caught once in
//    main.

#include <stdexcept>
#include <string>

namespace perimorph {

/// Base class for every error reported to the user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A case file (or command-line input) that cannot be run as written.
class InputError : public Error {
 public:
  using Error::Error;
};

/// An output folder or file that cannot be made or written (the message
/// names it and gives the system's reason, e.g. "No space left on device"),
/// or one another run is writing (io/output_lock.hpp).
class OutputError : public Error {
 public:
  using Error::Error;
};

/// The linear solver failed, or a non-finite value appeared in the solution.
class SolverError : public Error {
 public:
  using Error::Error;
};

/// A run stopped where it cannot go on (an increment that does not settle, a
/// component that cannot go on), which every process of a distributed run
/// meets at the same point with the same message: process 0 alone prints it.
class RunStopped : public Error {
 public:
  using Error::Error;
};

/// Thrown on the other processes of a distributed run when process 0 met an
/// error in what it alone does (la::on_process_zero): they stop where it
/// stops, silently, with the exit status of its error (`output`: an
/// OutputError's).
class StoppedByProcessZero : public Error {
 public:
  explicit StoppedByProcessZero(bool output_error)
      : Error("process 0 stopped the run"), output(output_error) {}
  bool output;
};

[[noreturn]] void assertion_failed(const char* expr, const char* file, int line, const std::string& message);

}  // namespace perimorph

#define PERIMORPH_ASSERT(cond, msg)                                               \
  do {                                                                            \
    if (!(cond)) ::perimorph::assertion_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (false)
