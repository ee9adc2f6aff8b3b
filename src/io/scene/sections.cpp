// The scene's sections and the keys each has: the schema's sections (keys.cpp), then [sweep]
// (its options; its axes are any numeric key, sweep_axes.cpp), [optimise] (its free
// parameters and options, optimise_section.cpp) and [census] (census_section.cpp).

#include <algorithm>

#include "scene_internal.hpp"

namespace vibromap::detail {

bool is_parameter_name(std::string_view name) {
  const auto& names = variable_parameter_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::string_view> all_sections() {
  std::vector<std::string_view> sections = scene_sections();
  sections.push_back(kOptimise);
  sections.push_back(kCensus);
  return sections;
}

bool is_free_parameter(std::string_view name) {
  const auto& names = free_parameter_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::optional<std::string_view> section_of(std::string_view key) {
  for (const Binding& b : bindings()) {
    if (b.info.key == key) return b.info.section;
  }
  const auto has = [&](const std::vector<std::string_view>& keys) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
  };
  if (has(sweep_option_keys())) return kSweep;
  if (has(optimise_option_keys())) return kOptimise;
  if (has(census_keys())) return kCensus;
  return std::nullopt;
}

const SceneKey& free_parameter_key(std::string_view name) { return find_key(name)->info; }

std::vector<std::string_view> schema_sections() {
  std::vector<std::string_view> sections;
  for (const Binding& b : bindings()) {
    if (sections.empty() || sections.back() != b.info.section) sections.push_back(b.info.section);
  }
  return sections;
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
  for (const Binding& b : bindings()) {
    if (b.info.section == section) keys.push_back(b.info.key);
  }
  return keys;
}

bool has_key(std::string_view section, std::string_view key) {
  if (section == kSweep) return is_sweep_option(key) || find_key(key) != nullptr;
  if (section == kOptimise) return std::find(optimise_keys().begin(), optimise_keys().end(), key) != optimise_keys().end();
  if (section == kCensus) return std::find(census_keys().begin(), census_keys().end(), key) != census_keys().end();
  return find_binding(section, key) != nullptr;
}

std::string_view partner_of(std::string_view section, std::string_view key) {
  if (section == kOptimise) return is_free_parameter(key) ? free_parameter_key(key).partner : std::string_view{};
  const Binding* b = find_binding(section, key);
  return b != nullptr ? b->info.partner : std::string_view{};
}

}  // namespace vibromap::detail
