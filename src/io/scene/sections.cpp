// The scene's sections and the keys each has: the point keys' sections (core/model/keys.hpp),
// then [sweep] (its options; its axes are any numeric key, sweep_axes.cpp), [optimise] (its
// free parameters and options, optimise_section.cpp) and [census] (census_section.cpp).

#include <algorithm>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {

std::vector<std::string_view> point_sections() {
  std::vector<std::string_view> sections;
  for (const Key k : Key::all()) {
    if (sections.empty() || sections.back() != k.info().section) sections.push_back(k.info().section);
  }
  return sections;
}

std::vector<std::string_view> all_sections() {
  std::vector<std::string_view> sections = scene_sections();
  sections.push_back(kOptimise);
  sections.push_back(kCensus);
  return sections;
}

std::optional<std::string_view> section_of(std::string_view key) {
  for (const Key k : Key::all()) {
    if (k.info().name == key) return k.info().section;
  }
  const auto has = [&](const std::vector<std::string_view>& keys) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  if (has(sweep_option_keys())) return kSweep;
  if (has(optimise_option_keys())) return kOptimise;
  if (has(census_keys())) return kCensus;
  return std::nullopt;
}

bool is_section(std::string_view name) {
  const auto sections = all_sections();
  return std::find(sections.begin(), sections.end(), name) != sections.end();
}

std::vector<std::string_view> keys_of(std::string_view section) {
  if (section == kSweep) return sweep_option_keys();
  if (section == kOptimise) return optimise_keys();
  if (section == kCensus) return census_keys();
  std::vector<std::string_view> keys;
  for (const Key k : Key::all()) {
    if (k.info().section == section) keys.push_back(k.info().name);
  }
  return keys;
}

bool has_key(std::string_view section, std::string_view key) {
  const auto listed = [&](const std::vector<std::string_view>& keys) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  if (section == kSweep) return is_sweep_option(key) || Key::find(key).has_value();
  if (section == kOptimise) return listed(optimise_option_keys()) || free_parameter(key).has_value();
  if (section == kCensus) return listed(census_keys());
  return Key::find(cat(section, ".", key)).has_value();
}

std::string_view partner_of(std::string_view section, std::string_view key) {
  if (section == kOptimise) {
    const std::optional<Key> k = free_parameter(key);
    return k ? k->info().partner : std::string_view{};
  }
  const std::optional<Key> k = Key::find(cat(section, ".", key));
  return k ? k->info().partner : std::string_view{};
}

std::optional<Key> free_parameter(std::string_view name) {
  const std::optional<Key> k = Key::find(name);
  return k && k->is_parameter() ? k : std::nullopt;
}

std::string pair_advice(const KeyInfo& a, const KeyInfo& b) {
  const auto in_unit = [](const KeyInfo& k) {
    return k.unit == "-" ? cat(k.name, " dimensionless") : cat(k.name, " in ", k.unit);
  };
  return cat("(", in_unit(a), ", or ", in_unit(b), ")");
}

}  // namespace vibromap::detail
