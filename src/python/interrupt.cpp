#include "interrupt.hpp"

#include <pybind11/pybind11.h>

#include <atomic>
#include <csignal>

#include "vibromap/core/integrate/cancel.hpp"

namespace vibromap::python {
namespace {

namespace py = pybind11;

// The signal recorded during a main-thread call (0: none). A lock-free atomic: the handler's
// store is async-signal-safe.
std::atomic<int> main_stop{0};
static_assert(std::atomic<int>::is_always_lock_free);

unsigned long main_thread_id = 0;

extern "C" void record_sigint(int signal) { main_stop.store(signal, std::memory_order_relaxed); }

// Our SIGINT handler while it lives, Python's again after; installed only on the main thread
// and only when Python handles SIGINT (not when it is ignored or left to the default action).
class SigintGuard {
 public:
  SigintGuard() {
    if (PyThread_get_thread_ident() != main_thread_id) return;
    struct sigaction current {};
    if (sigaction(SIGINT, nullptr, &current) != 0) return;
    if ((current.sa_flags & SA_SIGINFO) == 0 && (current.sa_handler == SIG_IGN || current.sa_handler == SIG_DFL))
      return;
    struct sigaction ours {};
    ours.sa_handler = record_sigint;
    sigemptyset(&ours.sa_mask);
    main_stop.store(0, std::memory_order_relaxed);
    active_ = sigaction(SIGINT, &ours, &previous_) == 0;
  }
  ~SigintGuard() {
    if (active_) sigaction(SIGINT, &previous_, nullptr);
  }
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

  const std::atomic<int>* flag() const { return active_ ? &main_stop : nullptr; }
  // Whether a SIGINT came while the guard was active.
  bool interrupted() const { return active_ && main_stop.load(std::memory_order_relaxed) != 0; }

 private:
  struct sigaction previous_ {};
  bool active_ = false;
};

// Hands the recorded SIGINT to Python's handler and raises what it raises (KeyboardInterrupt
// by default); raises KeyboardInterrupt when the handler returns quietly, since the call has
// no result to return. GIL held.
[[noreturn]] void raise_interrupt() {
  PyErr_SetInterruptEx(SIGINT);
  if (PyErr_CheckSignals() == 0) PyErr_SetNone(PyExc_KeyboardInterrupt);
  throw py::error_already_set();
}

}  // namespace

void remember_main_thread() { main_thread_id = PyThread_get_thread_ident(); }

void run_released(const std::function<void()>& work) {
  // A signal that came before the call (Python's handler recorded it) is honoured first.
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  bool cancelled = false;
  bool interrupted = false;
  {
    SigintGuard guard;
    py::gil_scoped_release release;
    const CancelScope scope(guard.flag());
    try {
      work();
    } catch (const Cancelled&) {
      cancelled = true;
    }
    interrupted = guard.interrupted();
  }
  if (cancelled) raise_interrupt();
  // A signal that came as the work ended: Python's handler runs at its next check.
  if (interrupted) PyErr_SetInterruptEx(SIGINT);
}

}  // namespace vibromap::python
