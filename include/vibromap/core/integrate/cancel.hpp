#pragma once
// Cancelling a long computation from outside the core (a stop signal in a campaign), without
// the core knowing who asks. A caller that wants its thread's computation stoppable opens a
// CancelScope over a flag (any non-zero value means "stop"; the campaigns give the farm's stop
// signal, parallel/signals.hpp); while the scope lives, the integrators' step loops poll the
// flag every kCancelPollSteps steps and throw Cancelled once it is set. Outside any scope the
// polls never throw, so a library user, a test or a command that is not a campaign is unaffected.
//
// Cancelled does not derive from std::exception on purpose: the handlers that turn an item's
// trouble into its result ("a cell's trouble is its status") catch std::exception, and a
// cancelled item must not become a failed result but leave the item unrecorded. Whoever opens
// the scope catches it (campaigns/stoppable.hpp).
//
// Cost: one AND and a compare per step, and every kCancelPollSteps steps a thread-local and a
// relaxed atomic load (a step costs ~1 us, so a stop is seen within a millisecond or so).

#include <atomic>

namespace vibromap {

// Thrown by a poll that finds its scope's flag set.
struct Cancelled {};

// Polls the flag every this many steps (a power of two).
inline constexpr long kCancelPollSteps = 256;
static_assert((kCancelPollSteps & (kCancelPollSteps - 1)) == 0);

// Makes the current thread's computations stoppable through `flag` (non-zero: stop) until
// the scope ends; scopes nest (the inner one's flag applies). flag == nullptr: not stoppable.
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<int>* flag) noexcept;
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<int>* previous_;
};

// Whether the current thread's scope asks to stop (false outside any scope).
bool cancel_requested() noexcept;
// Throws Cancelled when cancel_requested().
void check_cancel();

// The poll of a step loop: `step` counts the loop's steps; every kCancelPollSteps-th step
// checks the flag.
inline void poll_cancel(long step) {
  if ((step & (kCancelPollSteps - 1)) == 0) check_cancel();
}

}  // namespace vibromap
