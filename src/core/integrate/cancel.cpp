#include "vibromap/core/integrate/cancel.hpp"

namespace vibromap {
namespace {
thread_local const std::atomic<int>* t_flag = nullptr;
}  // namespace

CancelScope::CancelScope(const std::atomic<int>* flag) noexcept : previous_(t_flag) { t_flag = flag; }

CancelScope::~CancelScope() { t_flag = previous_; }

bool cancel_requested() noexcept {
  const std::atomic<int>* flag = t_flag;
  return flag != nullptr && flag->load(std::memory_order_relaxed) != 0;
}

void check_cancel() {
  if (cancel_requested()) throw Cancelled{};
}

}  // namespace vibromap
