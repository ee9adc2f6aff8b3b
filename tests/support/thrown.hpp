#pragma once
// The message of what a call throws, for tests that compare whole error lines.

#include <string>

namespace vibromap::test {

// The message of what `f` throws as E ("" when it throws nothing).
template <class E, class F>
std::string thrown(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace vibromap::test
