#pragma once
// Small text helpers shared by every layer's messages.

#include <string>
#include <string_view>

namespace vibromap {

// Concatenates string-like parts with one allocation. (Building messages with
// `"literal" + std::string&&` trips a false -Wrestrict in GCC 12's libstdc++, bug 105329;
// appending does not.)
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  s.reserve((std::string_view(parts).size() + ...));
  (s.append(std::string_view(parts)), ...);
  return s;
}

}  // namespace vibromap
