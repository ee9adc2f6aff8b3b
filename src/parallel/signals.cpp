#include "vibromap/parallel/signals.hpp"

#include <atomic>
#include <csignal>
#include <cstring>

#include <unistd.h>

#include "vibromap/parallel/exit_code.hpp"

namespace vibromap {
namespace {

std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the handler's store must be async-signal-safe");

std::atomic<int> g_at_once{0};  // open StopAtOnce sections
char g_remove[4096] = {};       // the file a StopAtOnce exit removes first ("" none)

// Async-signal-safe: write(2) and _exit(2) only.
void exit_at_once(int signal) {
  const char* line = signal == SIGINT    ? "vibromap: stopped by SIGINT while reading a file (no checkpoint needed)\n"
                     : signal == SIGUSR1 ? "vibromap: stopped by SIGUSR1 while reading a file (no checkpoint needed)\n"
                                         : "vibromap: stopped by SIGTERM while reading a file (no checkpoint needed)\n";
  if (g_remove[0] != '\0') ::unlink(g_remove);
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, line, std::strlen(line));
  ::_exit(code(ExitCode::stopped));
}

extern "C" void on_stop_signal(int signal) {
  int none = 0;
  g_stop_signal.compare_exchange_strong(none, signal);  // the first signal wins
  if (g_at_once.load() > 0) exit_at_once(g_stop_signal.load());
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // interrupted system calls (MPI's, HDF5's) resume
  for (const int signal : {SIGINT, SIGTERM, SIGUSR1}) sigaction(signal, &action, nullptr);
}

StopAtOnce::StopAtOnce(const std::string& remove) {
  if (remove.size() < sizeof g_remove) std::memcpy(g_remove, remove.c_str(), remove.size() + 1);
  g_at_once.fetch_add(1);
  if (const int signal = g_stop_signal.load(); signal != 0) exit_at_once(signal);
}

StopAtOnce::~StopAtOnce() {
  g_at_once.fetch_sub(1);
  g_remove[0] = '\0';
}

int stop_signal() { return g_stop_signal.load(); }

const std::atomic<int>& stop_flag() { return g_stop_signal; }

void request_stop(int signal) { on_stop_signal(signal); }

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGUSR1: return "SIGUSR1";
    default: return "signal " + std::to_string(signal);
  }
}

}  // namespace vibromap
