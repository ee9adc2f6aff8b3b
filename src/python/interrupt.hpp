#pragma once
// Long calls from Python: the GIL released while the core computes (so that threads of a
// concurrent.futures pool run at once), and Ctrl-C honoured within milliseconds.
//
// Python runs its signal handlers only in the main thread, between bytecodes, so a SIGINT that
// arrives during a long C++ call would wait for the call's end. While a call made from the main
// thread runs, a handler of our own records the signal in a flag that the core's integrators
// poll (core/integrate/cancel.hpp: CancelScope, the mechanism the campaigns use for their stop
// signals); the computation ends with Cancelled within a few hundred steps, Python's handler is
// restored and the signal handed to it (PyErr_SetInterruptEx), so KeyboardInterrupt (or the
// user's own SIGINT handler) follows as for pure Python code. Calls from other threads are not
// stoppable (Python delivers signals to the main thread only); nothing is written by the calls,
// so a stop leaves nothing half-done.

#include <functional>

namespace vibromap::python {

// Runs `work` with the GIL released and, from the main thread when Python handles SIGINT,
// stoppable by it. Called with the GIL held. On a stop throws pybind11::error_already_set with
// KeyboardInterrupt (or what the user's handler raised); exceptions of `work` pass through.
void run_released(const std::function<void()>& work);

// Records the main thread (call once, at import, from the importing thread: Python imports on
// the main thread unless a module is first imported from another).
void remember_main_thread();

}  // namespace vibromap::python
