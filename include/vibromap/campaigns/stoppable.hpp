#pragma once
// A campaign's solve(item), made stoppable: while it runs, the core's integrators poll the
// farm's stop flag (core/integrate/cancel.hpp over parallel/signals.hpp's stop_flag()), and a stop signal
// ends the item in flight within a few hundred steps instead of after it (an item can be one
// integration of hours). The core's Cancelled becomes the farm's ItemStopped: the item is not
// recorded, and the run checkpoints and exits with ExitCode::stopped. The core and the farm
// know nothing of each other; this is where they meet.

#include <cstdint>
#include <utility>

#include "vibromap/core/integrate/cancel.hpp"
#include "vibromap/parallel/farm.hpp"
#include "vibromap/parallel/signals.hpp"

namespace vibromap {

template <class Solve>
auto stoppable(Solve solve) {
  return [solve = std::move(solve)](std::uint64_t item) {
    const CancelScope scope(&stop_flag());
    try {
      return solve(item);
    } catch (const Cancelled&) {
      throw ItemStopped{};
    }
  };
}

}  // namespace vibromap
