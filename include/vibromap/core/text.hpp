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

// `text` cut to at most `max` characters for echoing user input in a one-line message: a
// longer text keeps its head and says how much was cut ("abc... (1048576 characters)").
inline std::string clip(std::string_view text, std::size_t max = 80) {
  if (text.size() <= max) return std::string(text);
  return cat(text.substr(0, max), "... (", std::to_string(text.size()), " characters)");
}

}  // namespace vibromap
