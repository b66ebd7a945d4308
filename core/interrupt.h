// SIGINT and SIGTERM as a clean stop: the first one only sets a flag, which long work polls
// between its steps (every Progress step, every pass of a render graph, and every atomic
// write before its rename, so no output is put in place after a stop); the work then throws
// Interrupted, whose unwinding
// removes temporary files (their owners' destructors), and main() exits 128 + the signal
// (130, 143) with one line. A second signal ends the process at once (the default action).
#pragma once

#include <csignal>
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

// Forgets the signal that arrived, for a program that goes on after a stop (the Python module:
// Ctrl-C ends a render, not the interpreter).
void clear_interrupt();

// For a program that keeps its own SIGINT handler (the Python interpreter's): sylva's handler
// for SIGINT while the object lives, the one it replaced put back after. A SIGINT meanwhile
// sets the flag (check_interrupt) and, unlike install_interrupt_handlers', leaves the handler
// in place, so a second one does not end the process. Main thread only (signals are delivered
// there); another thread's scope does nothing.
class ScopedInterruptHandler {
 public:
  ScopedInterruptHandler();
  ~ScopedInterruptHandler();
  ScopedInterruptHandler(const ScopedInterruptHandler&) = delete;
  ScopedInterruptHandler& operator=(const ScopedInterruptHandler&) = delete;

 private:
  bool m_installed = false;
  struct sigaction m_previous {};
};

}  // namespace sylva
