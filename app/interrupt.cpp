#include "app/interrupt.hpp"

#include <csignal>

namespace unsatmpm {

namespace {

volatile std::sig_atomic_t received = 0, count = 0;

extern "C" void record_signal(int signal) {
  received = signal;
  if (count < 1000) count = count + 1;
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, record_signal);
  std::signal(SIGTERM, record_signal);
}

int interrupt_signal() { return received; }

int interrupt_count() { return count; }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

}  // namespace unsatmpm
