// The names of [sweep] axes: which key each axis sweeps. An axis is any real or integer key of
// the key table (core/model/keys.hpp), named in full ("forcing.omega", quoted, or TOML's dotted forcing.omega, which is
// the table forcing with the key omega) or by the key alone when only one section has it
// (E1, omega). The reading of an axis's values is sweep_section.cpp's.

#include <algorithm>
#include <array>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

// The axes of the first versions, first in the default order in this order, so that a scene
// of that time keeps its map's layout; any other axis follows in the key table's order.
constexpr std::array<std::string_view, 7> kFirstAxes = {"contact.E1", "contact.E2", "contact.R1", "contact.R2",
                                                        "system.m2",  "system.k2",  "system.omega2"};

bool is_point_section(std::string_view name) {
  const auto sections = point_sections();
  return std::find(sections.begin(), sections.end(), name) != sections.end();
}

// What a "did you mean" may suggest in [sweep]: the options, then every numeric key by its
// name and in full.
const std::vector<std::string>& sweep_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n(sweep_option_keys().begin(), sweep_option_keys().end());
    for (const Key k : Key::all()) {
      if (k.info().is_numeric()) n.emplace_back(k.info().name);
    }
    for (const Key k : Key::all()) {
      if (k.info().is_numeric()) n.push_back(k.full_name());
    }
    return n;
  }();
  return names;
}

[[noreturn]] void fail_unknown_axis(const std::string& loc, std::string_view name) {
  std::string msg = cat(loc, ": unknown key '", clip(name), "' in [sweep]");
  const auto homes = std::count_if(Key::all().begin(), Key::all().end(), [&](Key k) { return k.info().name == name; });
  if (homes > 1) {
    msg += " (several sections have it: name it section.key)";
  } else if (const auto hint = closest(name, views(sweep_names()))) {
    msg += cat(" (did you mean '", *hint, "'?)");
  }
  std::vector<std::string> sections;
  for (const std::string_view s : point_sections()) sections.push_back(cat("[", s, "]"));
  fail(cat(msg, "; an axis is any real or integer key of ", join(views(sections), ", "),
           ", as section.key or by the key alone when only one section has it; the options are ",
           join(sweep_option_keys(), ", ")));
}

// The key an axis name stands for: numeric, or a categorical parameter key (contact.law).
Key axis_key(std::string_view name, const std::string& loc) {
  const std::optional<Key> k = Key::find(name);
  if (!k) fail_unknown_axis(loc, name);
  if (!k->is_axis()) {
    fail(cat(loc, ": [sweep] ", k->full_name(), " cannot be an axis: it is ", k->info().allowed(),
             ", not a number; run one sweep per value"));
  }
  return *k;
}

// Refuses an axis whose key, or whose pair partner, is an axis already.
void check_new_axis(const std::vector<SweepAxisEntry>& entries, Key key, const std::string& given,
                    const std::string& loc) {
  const KeyInfo& b = key.info();
  for (const SweepAxisEntry& e : entries) {
    const KeyInfo& k = e.key.info();
    if (e.key == key) {
      fail(cat(loc, ": [sweep] ", k.full_name(), " is given twice (as ", clip(e.given), " and ", clip(given),
               "): give each axis once"));
    }
    if (k.section == b.section && k.partner == b.name) {
      fail(cat(loc, ": [sweep] both ", k.name, " and ", b.name, " given as axes: sweep only one ", pair_advice(k, b)));
    }
  }
}

}  // namespace

std::size_t key_rank(Key k) {
  const std::string key = k.full_name();
  const auto it = std::find(kFirstAxes.begin(), kFirstAxes.end(), key);
  return it != kFirstAxes.end() ? static_cast<std::size_t>(it - kFirstAxes.begin()) : kFirstAxes.size() + k.index();
}

std::vector<std::string_view> first_axes() {
  std::vector<std::string_view> names;
  for (const std::string_view key : kFirstAxes) names.push_back(key.substr(key.find('.') + 1));
  return names;
}

void for_each_key_entry(const toml::table& section, bool (*is_option)(std::string_view),
                        const std::function<void(std::string, std::string, const toml::node&)>& f) {
  for (auto&& [key, node] : section) {
    const std::string_view name = key.str();
    if (is_option(name)) continue;
    const toml::table* inner_table = node.as_table();
    if (inner_table != nullptr && is_point_section(name)) {
      for (auto&& [inner, value] : *inner_table) f(cat(name, ".", inner.str()), cat(name, ".", toml_key(inner.str())), value);
    } else {
      f(std::string(name), toml_key(name), node);
    }
  }
}

bool is_sweep_option(std::string_view key) {
  return std::find(sweep_option_keys().begin(), sweep_option_keys().end(), key) != sweep_option_keys().end();
}

std::vector<SweepAxisEntry> sweep_axis_entries(const toml::table& sweep, const Context& ctx) {
  std::vector<SweepAxisEntry> entries;
  for_each_key_entry(sweep, is_sweep_option, [&](std::string given, std::string text_key, const toml::node& node) {
    const Key k = axis_key(given, origin(ctx, kSweep, given, node));
    check_new_axis(entries, k, given, where(ctx, node));
    entries.push_back({std::move(given), std::move(text_key), k, &node});
  });
  if (entries.size() > kMaxSweepAxes) {
    fail(cat(where(ctx, sweep), ": [sweep] has ", std::to_string(entries.size()), " axes: at most ",
             std::to_string(kMaxSweepAxes)));
  }
  std::stable_sort(entries.begin(), entries.end(), [](const SweepAxisEntry& a, const SweepAxisEntry& b) {
    return key_rank(a.key) < key_rank(b.key);
  });
  return entries;
}

void erase_key_entries(toml::table& section, Key target, bool (*is_option)(std::string_view)) {
  const auto replaced = [&](std::string_view given) {
    const std::optional<Key> k = Key::find(given);
    return k && (*k == target || (k->info().section == target.info().section && k->info().name == target.info().partner));
  };
  std::vector<std::string> doomed;
  for (auto&& [key, node] : section) {
    if (is_option(key.str())) continue;
    toml::table* inner_table = node.as_table();
    if (inner_table != nullptr && is_point_section(key.str())) {
      std::vector<std::string> inner_doomed;
      for (auto&& [inner, value] : *inner_table)
        if (replaced(cat(key.str(), ".", inner.str()))) inner_doomed.emplace_back(inner.str());
      for (const std::string& inner : inner_doomed) inner_table->erase(inner);
      if (inner_table->empty()) doomed.emplace_back(key.str());
    } else if (replaced(key.str())) {
      doomed.emplace_back(key.str());
    }
  }
  for (const std::string& key : doomed) section.erase(key);
}

void erase_sweep_axis(toml::table& sweep, std::string_view name, const std::string& loc) {
  erase_key_entries(sweep, axis_key(name, loc), is_sweep_option);
}

}  // namespace vibromap::detail

namespace vibromap {

CommandAxis command_axis(std::string option, std::string_view name, std::vector<double> values, AxisScale scale,
                         bool parameter_only) {
  const std::string what = parameter_only ? "a parameter: a real key of [system], [contact] or [forcing]"
                                          : "a real or integer key, or contact.law";
  const std::optional<Key> k = Key::find(name);
  if (!k) {
    std::vector<std::string> names;  // what a "did you mean" may suggest: names, then full names
    for (const Key other : Key::all())
      if (parameter_only ? other.is_parameter() : other.is_axis()) names.emplace_back(other.info().name);
    for (const Key other : Key::all())
      if (parameter_only ? other.is_parameter() : other.is_axis()) names.push_back(other.full_name());
    std::string msg = cat(option, ": unknown key '", clip(name), "'");
    if (const auto hint = detail::closest(name, detail::views(names))) msg += cat(" (did you mean '", *hint, "'?)");
    detail::fail(cat(msg, "; it must be ", what, ", by its name alone when only one section has it (see 'vibromap keys')"));
  }
  if (parameter_only && !k->is_parameter())
    detail::fail(cat(option, ": ", k->full_name(), " cannot be continued: the key must be ", what));
  if (!k->is_axis())
    detail::fail(cat(option, ": ", k->full_name(), " cannot be stepped: it is ", k->info().allowed(), ", not a number"));
  for (const double v : values)
    if (const std::string r = k->check(v); !r.empty()) detail::fail(cat(option, ": ", r));
  try {
    return {make_axis(*k, std::move(values), scale), std::move(option)};
  } catch (const std::invalid_argument& e) {
    detail::fail(cat(option, ": ", e.what()));
  }
}

}  // namespace vibromap
