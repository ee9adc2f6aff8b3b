#pragma once
// Stop signals of a campaign. SIGINT, SIGTERM and SIGUSR1 all mean the same: stop handing out
// work, abandon the items in flight (their solvers poll stop_flag(): farm.hpp, ItemStopped),
// write a final checkpoint, exit with ExitCode::stopped. The handlers only record the signal
// (an async-signal-safe store); the farm and the solvers poll it.
//
// install_stop_handlers() is called first thing in main for the campaign commands, before MPI
// starts or the scene is read, so a signal that arrives at any instant of a run is honoured
// (the farm sees it when it starts and stops at once, after its first checkpoint). Commands
// that are not campaigns keep the default actions (Ctrl-C ends `vibromap run` at once).
// Later signals are ignored while the first is being honoured; kill -9 is always safe
// (what was checkpointed is kept).

#include <atomic>
#include <string>

namespace vibromap {

void install_stop_handlers();
// The first stop signal received (SIGINT, SIGTERM or SIGUSR1), 0 when none.
int stop_signal();
// The flag stop_signal() reads, for a solver that polls it without knowing this layer (the
// core's CancelScope, opened by the campaigns around each item).
const std::atomic<int>& stop_flag();
// Records `signal` as if it had arrived (the farm on rank 0, when another rank was signalled).
void request_stop(int signal);
// While one lives, a stop signal ends the process at once: one line on stderr, exit 3
// (ExitCode::stopped), no final checkpoint. For work that cannot poll the stop flag and whose
// interruption loses nothing: reading an existing file through the HDF5 library, which a damaged
// file can send into an endless loop (HDF5 1.10 walks a global heap whose free-space object has
// size 0 for ever). A signal that came before the section opens ends the process as it opens.
// The file is left as kill -9 would leave it: whole, as of its last checkpoint; `remove` (the
// run's lock file, which kill -9 would leave behind) is removed first.
class StopAtOnce {
 public:
  explicit StopAtOnce(const std::string& remove = {});
  ~StopAtOnce();
  StopAtOnce(const StopAtOnce&) = delete;
  StopAtOnce& operator=(const StopAtOnce&) = delete;
};
// "SIGTERM", "SIGINT", "SIGUSR1", or "signal N".
std::string signal_name(int signal);

}  // namespace vibromap
