#include "core/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <string>

namespace sylva {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int signal) {
  g_signal = signal;
  std::signal(signal, SIG_DFL);  // a second one ends the process
}

extern "C" void on_signal_keep(int signal) {
  g_signal = signal;
}

}  // namespace

Interrupted::Interrupted(int signal)
    : std::runtime_error(std::string("interrupted by ") + (signal == SIGINT    ? "SIGINT"
                                                           : signal == SIGTERM ? "SIGTERM"
                                                                               : "a signal")),
      m_signal(signal) {}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // system calls continue; the work stops at its next check
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() {
  return g_signal;
}

void check_interrupt() {
  if (g_signal != 0) throw Interrupted(g_signal);
}

void clear_interrupt() {
  g_signal = 0;
}

ScopedInterruptHandler::ScopedInterruptHandler() {
  if (gettid() != getpid()) return;  // not the main thread
  struct sigaction action {};
  action.sa_handler = on_signal_keep;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  m_installed = sigaction(SIGINT, &action, &m_previous) == 0;
}

ScopedInterruptHandler::~ScopedInterruptHandler() {
  if (m_installed) sigaction(SIGINT, &m_previous, nullptr);
}

}  // namespace sylva
