#pragma once
// Small text helpers shared by every layer's messages.

#include <array>
#include <charconv>
#include <cstdio>
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

// The one number formatter of messages, tables and provenance text.
// `x` to `digits` significant digits, as printf's %.*g and an ostream's setprecision(digits)
// print it: number(7.23) is "7.23", number(1.0 / 3, 3) "0.333", number(x, 17) the double itself.
inline std::string number(double x, int digits = 6) {
  std::array<char, 64> buf{};
  const int n = std::snprintf(buf.data(), buf.size(), "%.*g", digits, x);
  return std::string(buf.data(), static_cast<std::size_t>(n > 0 ? n : 0));
}

// `x` as printf writes it with `spec`, for fixed layouts ("%.4f", "%-10.5g", "%+-16.6f").
inline std::string printf_number(double x, const char* spec = "%.6g") {
  std::array<char, 64> buf{};
  const int n = std::snprintf(buf.data(), buf.size(), spec, x);
  return std::string(buf.data(), static_cast<std::size_t>(n > 0 ? n : 0));
}

// The shortest text that reads back to the same double: "0.1", "1e-10", "1000".
inline std::string shortest(double x) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), res.ptr);
}

// As shortest(), but always written as a float, as TOML and JSON readers want one: "1000.0",
// "0.1", "1e-10".
inline std::string float_text(double x) {
  std::string t = shortest(x);
  if (t.find_first_of(".en") == std::string::npos) t += ".0";  // not "1e-10", "inf", "nan"
  return t;
}

}  // namespace vibromap
