// SIGINT and SIGTERM as a clean stop: the first one only sets a flag, which long work polls
// between its steps (every Progress step, and every atomic write before its rename, so no
// output is put in place after a stop); the work then throws Interrupted, whose unwinding
// removes temporary files (their owners' destructors), and main() exits 128 + the signal
// (130, 143) with one line. A second signal ends the process at once (the default action).
#pragma once

#include <stdexcept>

namespace sylva {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal() const { return m_signal; }

 private:
  int m_signal;
};

// Installs the handlers for SIGINT and SIGTERM (once, in main).
void install_interrupt_handlers();

// The signal that arrived (SIGINT or SIGTERM), or 0.
int interrupt_signal();

// Throws Interrupted when a signal arrived.
void check_interrupt();

}  // namespace sylva
