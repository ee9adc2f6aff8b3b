#pragma once
// How a row of an options section ([optimise], [census]) reads its key into the section's
// options struct O, and writes the value read back as canonical text (identity.cpp). Private
// to src/io/scene.

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {

template <class O, auto... Members>
void read_real_field(O& o, const KeyInfo& k, const toml::node& node, const std::string& loc) {
  (o.*....*Members) = read_real(k, node, loc);
}

template <class O, auto... Members>
void read_integer_field(O& o, const KeyInfo& k, const toml::node& node, const std::string& loc) {
  using T = std::remove_cvref_t<decltype((o.*....*Members))>;
  // A whole float such as 200.0 is accepted; the field's type bounds it too.
  const double x = number_of(node).value_or(std::numeric_limits<double>::quiet_NaN());
  constexpr long long kFieldMax = static_cast<unsigned long long>(std::numeric_limits<T>::max()) >
                                          static_cast<unsigned long long>(std::numeric_limits<long long>::max())
                                      ? std::numeric_limits<long long>::max()
                                      : static_cast<long long>(std::numeric_limits<T>::max());
  if (const std::string need = k.requirement(x, kFieldMax); !need.empty()) fail(cat(loc, ": ", need));
  (o.*....*Members) = static_cast<T>(x);
}

template <class O, auto Member>
void read_bool_field(O& o, const KeyInfo& k, const toml::node& node, const std::string& loc) {
  o.*Member = read_boolean(k, node, loc) != 0;
}

template <class O, auto Parse, auto Member>
void read_choice_field(O& o, const KeyInfo& k, const toml::node& node, const std::string& loc) {
  o.*Member = Parse(k.choices.at(static_cast<std::size_t>(read_choice(k, node, loc))));
}

// How a row reads its key, and writes back the value read as canonical text (identity.cpp).
template <class O>
struct RowAccess {
  void (*read)(O&, const KeyInfo&, const toml::node&, const std::string&);
  std::string (*text)(const O&, const KeyInfo&);
};

template <class O, auto... Members>
RowAccess<O> real_field() {
  return {read_real_field<O, Members...>, [](const O& o, const KeyInfo&) { return shortest((o.*....*Members)); }};
}

template <class O, auto... Members>
RowAccess<O> integer_field() {
  return {read_integer_field<O, Members...>, [](const O& o, const KeyInfo&) { return std::to_string((o.*....*Members)); }};
}

template <class O, auto Member>
RowAccess<O> bool_field() {
  return {read_bool_field<O, Member>, [](const O& o, const KeyInfo&) { return std::string(o.*Member ? "true" : "false"); }};
}

template <class O, auto Parse, auto Member>
RowAccess<O> choice_field() {
  return {read_choice_field<O, Parse, Member>, [](const O& o, const KeyInfo&) { return to_string(o.*Member); }};
}


// Reads the keys of `rows` present in the section table `sec` into o.
template <class O>
void read_rows(O& o, const std::vector<OptionRow<O>>& rows, const toml::table& sec, const Context& ctx) {
  for (const OptionRow<O>& row : rows) {
    if (const toml::node* node = sec.get(row.info.name)) row.read(o, row.info, *node, locate(ctx, row.info, *node));
  }
}

// "SECTION.KEY = VALUE" for every row, the value as read (canonical text for the run identity).
template <class O>
std::vector<std::string> row_lines(std::string_view section, const O& o, const std::vector<OptionRow<O>>& rows) {
  std::vector<std::string> lines;
  for (const OptionRow<O>& row : rows) lines.push_back(cat(section, ".", row.info.name, " = ", row.text(o, row.info)));
  return lines;
}

}  // namespace vibromap::detail
