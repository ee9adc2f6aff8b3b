#include "vibromap/io/scene/identity.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap {
namespace {


constexpr std::size_t kShownValue = 40;  // characters of a value (or key) shown in a difference

// A value as the identity writes it: a real in its shortest form, a choice by its name.
std::string canonical_value(const KeyInfo& k, double v) {
  switch (k.type) {
    case KeyType::real: return shortest(v);
    case KeyType::integer: return std::to_string(static_cast<long long>(v));
    case KeyType::choice: return std::string(k.choices.at(static_cast<std::size_t>(v)));
    case KeyType::boolean: return v != 0.0 ? "true" : "false";
  }
  return {};
}

void add_point_lines(const Scene& scene, std::vector<std::string>& lines) {
  for (const Key k : Key::all()) {
    const int component = k.component();
    if (component >= 0 && !scene.initial_given.at(static_cast<std::size_t>(component))) continue;
    const std::optional<double> v = k.stored(scene.params, scene.options);
    if (!v || (!k.info().identity_at_default && v == k.stored(Parameters{}, PointOptions{}))) continue;
    lines.push_back(cat(k.full_name(), " = ", canonical_value(k.info(), *v)));
  }
}

void add_sweep_lines(const SweepOptions& sweep, std::vector<std::string>& lines) {
  for (std::size_t d = 0; d < sweep.axes.size(); ++d) {
    const Axis& a = sweep.axes[d];
    std::string values;
    for (const double v : a.values) values += cat(values.empty() ? "" : ", ", shortest(v));
    lines.push_back(cat("sweep.axis.", std::to_string(d), " = ", a.key, " ", to_string(a.scale), " [", values, "]"));
  }
  std::string store;
  for (const Quantity q : sweep.store) store += cat(store.empty() ? "" : ", ", to_string(q));
  lines.push_back(cat("sweep.store = [", store, "]"));
  for (std::string& line : detail::refine_lines(sweep)) lines.push_back(std::move(line));
}

// "key = value" lines as a map from key to value.
std::map<std::string, std::string, std::less<>> parse_lines(std::string_view text) {
  std::map<std::string, std::string, std::less<>> out;
  while (!text.empty()) {
    const std::size_t end = std::min(text.find('\n'), text.size());
    const std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    const std::size_t eq = line.find(" = ");
    if (eq != std::string_view::npos) out.emplace(line.substr(0, eq), line.substr(eq + 3));
  }
  return out;
}

std::string shown(const std::string* value, std::string_view where) {
  return value == nullptr ? cat("not in ", where) : cat(clip(*value, kShownValue), " in ", where);
}

}  // namespace

std::string canonical_text(const Scene& scene, IdentityScope scope) {
  std::vector<std::string> lines;
  add_point_lines(scene, lines);
  if (scene.sweep) add_sweep_lines(*scene.sweep, lines);
  if (scene.census) {
    for (std::string& line : detail::census_lines(*scene.census)) lines.push_back(std::move(line));
  }
  if (scope == IdentityScope::optimise && scene.optimise) {
    for (std::string& line : detail::optimise_lines(*scene.optimise)) lines.push_back(std::move(line));
    // min_soft_fraction censuses every point with [census]'s options, the defaults when the
    // scene has none: they define the result, so they are named even when not given.
    if (scene.optimise->min_soft_fraction > 0.0 && !scene.census) {
      for (std::string& line : detail::census_lines(CensusOptions{})) lines.push_back(std::move(line));
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string text;
  for (const std::string& line : lines) text += cat(line, "\n");
  return text;
}

std::vector<std::string> canonical_differences(std::string_view recorded, std::string_view current) {
  const auto file = parse_lines(recorded), scene = parse_lines(current);
  std::map<std::string_view, std::pair<const std::string*, const std::string*>> keys;
  for (const auto& [k, v] : file) keys[k].first = &v;
  for (const auto& [k, v] : scene) keys[k].second = &v;
  std::vector<std::string> out;
  for (const auto& [key, values] : keys) {
    const auto& [in_file, in_scene] = values;
    if (in_file != nullptr && in_scene != nullptr && *in_file == *in_scene) continue;
    out.push_back(cat(clip(key, kShownValue), " (", shown(in_file, "the file"), ", ", shown(in_scene, "the scene"), ")"));
  }
  return out;
}

}  // namespace vibromap
