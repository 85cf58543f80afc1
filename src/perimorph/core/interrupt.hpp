#pragma once
// A stop asked for from outside (SIGINT, SIGTERM): the program's signal
// handler records it (async-signal-safe), the run loop looks at it between
// solves and stops there with Interrupted, its output files in step (every
// written increment has its CSV row, PVD entry and VTU).

#include "perimorph/core/error.hpp"

namespace perimorph {

/// Installs handlers for SIGINT and SIGTERM that record a stop request. A
/// second signal while one is pending ends the process at once (the default
/// action), for a solve that takes too long to reach the next check.
void install_stop_handlers();
/// The signal of a pending stop request, 0 if none.
int stop_requested();
/// Records a stop request as the handler does (tests), or clears it (0).
void set_stop_request(int signal);
/// "SIGINT", "SIGTERM", or "signal N".
std::string signal_name(int signal);

/// The run stopped at a stop request; `signal` is the one that asked.
class Interrupted : public Error {
 public:
  Interrupted(const std::string& what, int sig) : Error(what), signal(sig) {}
  int signal;
};

}  // namespace perimorph
