#include "perimorph/core/interrupt.hpp"

#include <csignal>
#include <string>

namespace perimorph {
namespace {

volatile std::sig_atomic_t pending = 0;

extern "C" void on_stop_signal(int sig) {
  if (pending != 0) {  // asked twice: the default action, now
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  pending = sig;
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

int stop_requested() {
  return static_cast<int>(pending);
}

void set_stop_request(int signal) {
  pending = signal;
}

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

}  // namespace perimorph
