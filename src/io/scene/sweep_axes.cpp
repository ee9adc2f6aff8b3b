// The names of [sweep] axes: which key each axis sweeps. An axis is any real or integer key of
// the schema, named in full ("forcing.omega", quoted, or TOML's dotted forcing.omega, which is
// the table forcing with the key omega) or by the key alone when only one section has it
// (E1, omega). The reading of an axis's values is sweep_section.cpp's.

#include <algorithm>
#include <array>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

// The axes of the first versions, first in the default order in this order, so that a scene
// of that time keeps its map's layout; any other axis follows in the schema's order.
constexpr std::array<std::string_view, 7> kFirstAxes = {"contact.E1", "contact.E2", "contact.R1", "contact.R2",
                                                        "system.m2",  "system.k2",  "system.omega2"};

std::size_t default_rank(const Binding& b) {
  const std::string key = full_key(b.info);
  const auto it = std::find(kFirstAxes.begin(), kFirstAxes.end(), key);
  return it != kFirstAxes.end() ? static_cast<std::size_t>(it - kFirstAxes.begin()) : kFirstAxes.size() + index_of(b);
}

bool is_schema_section(std::string_view name) {
  const auto sections = schema_sections();
  return std::find(sections.begin(), sections.end(), name) != sections.end();
}

// What a "did you mean" may suggest in [sweep]: the options, then every numeric key by its
// name and in full.
const std::vector<std::string>& sweep_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n(sweep_option_keys().begin(), sweep_option_keys().end());
    for (const Binding& b : bindings()) {
      if (is_numeric(b.info)) n.emplace_back(b.info.key);
    }
    for (const Binding& b : bindings()) {
      if (is_numeric(b.info)) n.push_back(full_key(b.info));
    }
    return n;
  }();
  return names;
}

[[noreturn]] void fail_unknown_axis(const std::string& loc, std::string_view name) {
  std::string msg = cat(loc, ": unknown key '", clip(name), "' in [sweep]");
  const auto homes = std::count_if(bindings().begin(), bindings().end(), [&](const Binding& b) { return b.info.key == name; });
  if (homes > 1) {
    msg += " (several sections have it: name it section.key)";
  } else if (const auto hint = closest(name, views(sweep_names()))) {
    msg += cat(" (did you mean '", *hint, "'?)");
  }
  std::vector<std::string> sections;
  for (const std::string_view s : schema_sections()) sections.push_back(cat("[", s, "]"));
  fail(cat(msg, "; an axis is any real or integer key of ", join(views(sections), ", "),
           ", as section.key or by the key alone when only one section has it; the options are ",
           join(sweep_option_keys(), ", ")));
}

// The key an axis name stands for: numeric, or a categorical parameter key (contact.law).
const Binding& axis_binding(std::string_view name, const std::string& loc) {
  const Binding* b = find_key(name);
  if (b == nullptr) fail_unknown_axis(loc, name);
  if (!is_numeric(b->info) && !is_categorical_axis(b->info)) {
    fail(cat(loc, ": [sweep] ", full_key(b->info), " cannot be an axis: it is ", b->info.allowed(),
             ", not a number; run one sweep per value"));
  }
  return *b;
}

// Calls f(given, text_key, node) for every axis of a [sweep] table: each key but the options,
// and each key of a section's table (the dotted form forcing.omega = { ... }).
template <class F>
void for_each_axis(const toml::table& sweep, F f) {
  for (auto&& [key, node] : sweep) {
    const std::string_view name = key.str();
    if (is_sweep_option(name)) continue;
    const toml::table* section = node.as_table();
    if (section != nullptr && is_schema_section(name)) {
      for (auto&& [inner, value] : *section) f(cat(name, ".", inner.str()), cat(name, ".", toml_key(inner.str())), value);
    } else {
      f(std::string(name), toml_key(name), node);
    }
  }
}

// Refuses an axis whose key, or whose pair partner, is an axis already.
void check_new_axis(const std::vector<SweepAxisEntry>& entries, const Binding& b, const std::string& given,
                    const std::string& loc) {
  for (const SweepAxisEntry& e : entries) {
    const SceneKey& k = e.binding->info;
    if (e.binding == &b) {
      fail(cat(loc, ": [sweep] ", full_key(k), " is given twice (as ", clip(e.given), " and ", clip(given),
               "): give each axis once"));
    }
    if (k.section == b.info.section && k.partner == b.info.key) {
      fail(cat(loc, ": [sweep] both ", k.key, " and ", b.info.key, " given as axes: sweep only one ",
               pair_advice(k, b.info)));
    }
  }
}

}  // namespace

std::vector<std::string_view> first_axes() {
  std::vector<std::string_view> names;
  for (const std::string_view key : kFirstAxes) names.push_back(key.substr(key.find('.') + 1));
  return names;
}

bool is_sweep_option(std::string_view key) {
  return std::find(sweep_option_keys().begin(), sweep_option_keys().end(), key) != sweep_option_keys().end();
}

std::vector<SweepAxisEntry> sweep_axis_entries(const toml::table& sweep, const Context& ctx) {
  std::vector<SweepAxisEntry> entries;
  for_each_axis(sweep, [&](std::string given, std::string text_key, const toml::node& node) {
    const Binding& b = axis_binding(given, origin(ctx, kSweep, given, node));
    check_new_axis(entries, b, given, where(ctx, node));
    entries.push_back({std::move(given), std::move(text_key), &b, &node});
  });
  if (entries.size() > kMaxSweepAxes) {
    fail(cat(where(ctx, sweep), ": [sweep] has ", std::to_string(entries.size()), " axes: at most ",
             std::to_string(kMaxSweepAxes)));
  }
  std::stable_sort(entries.begin(), entries.end(), [](const SweepAxisEntry& a, const SweepAxisEntry& b) {
    return default_rank(*a.binding) < default_rank(*b.binding);
  });
  return entries;
}

void erase_sweep_axis(toml::table& sweep, std::string_view name, const std::string& loc) {
  const Binding& target = axis_binding(name, loc);
  const auto replaced = [&](std::string_view given) {
    const Binding* b = find_key(given);
    return b == &target || (b != nullptr && b->info.section == target.info.section && b->info.key == target.info.partner);
  };
  std::vector<std::string> doomed;
  for (auto&& [key, node] : sweep) {
    if (is_sweep_option(key.str())) continue;
    toml::table* section = node.as_table();
    if (section != nullptr && is_schema_section(key.str())) {
      std::vector<std::string> inner_doomed;
      for (auto&& [inner, value] : *section)
        if (replaced(cat(key.str(), ".", inner.str()))) inner_doomed.emplace_back(inner.str());
      for (const std::string& inner : inner_doomed) section->erase(inner);
      if (section->empty()) doomed.emplace_back(key.str());
    } else if (replaced(key.str())) {
      doomed.emplace_back(key.str());
    }
  }
  for (const std::string& key : doomed) sweep.erase(key);
}

}  // namespace vibromap::detail
