// TOML text for the scene folder: numbers in their shortest round-trip form, strings and keys
// quoted as TOML wants them, values and inline tables as a person writes them, and the
// "did you mean" hint of a one-line message.

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {

std::string join(const std::vector<std::string_view>& items, std::string_view sep, std::string_view quote) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += sep;
    out += quote;
    out += items[i];
    out += quote;
  }
  return out;
}

std::string unit_suffix(std::string_view unit) {
  return unit.empty() || unit == "-" ? std::string() : cat(" (", unit, ")");
}

std::vector<std::string_view> views(const std::vector<std::string>& strings) {
  return {strings.begin(), strings.end()};
}

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return std::string(s.substr(first, last - first + 1));
}

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Optimal-string-alignment edit distance (Levenshtein plus adjacent transpositions),
// case-insensitive: "omgea" is 1 from "omega".
std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lower(a_in), b = lower(b_in);
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

// The candidate closest to `name`, when it is close enough to be a likely typo.
std::optional<std::string_view> closest(std::string_view name, const std::vector<std::string_view>& candidates) {
  const std::size_t limit = name.size() <= 3 ? 1 : 2;
  std::optional<std::string_view> best;
  std::size_t best_d = limit + 1;
  for (std::string_view c : candidates) {
    const std::size_t gap = name.size() > c.size() ? name.size() - c.size() : c.size() - name.size();
    if (gap > limit) continue;  // the distance is at least the length difference (and a long name costs no time)
    const std::size_t d = edit_distance(name, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

// A TOML basic string: "..." with quotes, backslashes and control characters escaped.
std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      std::array<char, 8> buf{};
      std::snprintf(buf.data(), buf.size(), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf.data();
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A key as TOML text: bare when it can be, else quoted.
std::string toml_key(std::string_view k) {
  const bool bare = !k.empty() && std::all_of(k.begin(), k.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
  });
  return bare ? std::string(k) : toml_string(k);
}

namespace {

// Where a key goes in an inline table's text: an axis's (or a free parameter's) fields in the
// order a person writes them (toml++ keeps a table's keys sorted), other keys after them in that sorted order.
std::size_t field_rank(std::string_view key) {
  constexpr std::array<std::string_view, 7> order = {"from", "to", "n", "values", "min", "max", "scale"};
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), key) - order.begin());
}

std::string table_text(const toml::table& t) {
  std::vector<std::pair<std::string_view, const toml::node*>> items;
  for (auto&& [k, v] : t) items.emplace_back(k.str(), &v);
  std::stable_sort(items.begin(), items.end(),
                   [](const auto& a, const auto& b) { return field_rank(a.first) < field_rank(b.first); });
  std::string out = "{";
  for (std::size_t i = 0; i < items.size(); ++i) {
    out += cat(i > 0 ? ", " : " ", toml_key(items[i].first), " = ", node_text(*items[i].second));
  }
  return out + (items.empty() ? "}" : " }");
}

}  // namespace

// A value as TOML text; floats in their shortest round-trip form (toml++ prints 17 digits),
// arrays and tables (also nested) as inline ones.
std::string node_text(const toml::node& node) {
  if (const auto* f = node.as_floating_point()) return float_text(f->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* s = node.as_string()) return toml_string(s->get());
  if (const auto* a = node.as_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < a->size(); ++i) out += cat(i > 0 ? ", " : "", node_text(*a->get(i)));
    return out + "]";
  }
  if (const auto* t = node.as_table()) return table_text(*t);
  std::ostringstream os;
  os << toml::node_view<const toml::node>(node);
  return os.str();
}

std::string clipped_text(const toml::node& node) { return clip(node_text(node), 100); }


}  // namespace vibromap::detail
