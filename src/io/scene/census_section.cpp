// The [census] section of a scene: the options of CensusOptions, each a row like [optimise]'s.
// The box sides x1, x2, v1, v2 are arrays [lo, hi]; the others are numbers.

#include <algorithm>
#include <cmath>

#include "option_fields.hpp"
#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

using C = CensusOptions;
using Side = std::optional<std::array<double, 2>> CensusOptions::*;

constexpr std::string_view kSideForm = "an array [lo, hi] of two finite numbers with lo <= hi and a finite hi - lo";

template <Side Member>
void read_side(C& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  const toml::array* a = node.as_array();
  std::optional<double> lo, hi;
  if (a != nullptr && a->size() == 2) {
    lo = number_of(*a->get(0));
    hi = number_of(*a->get(1));
  }
  if (!lo || !hi || !std::isfinite(*lo) || !std::isfinite(*hi) || *lo > *hi || !std::isfinite(*hi - *lo))
    fail(cat(loc, ": must be ", kSideForm));
  o.*Member = std::array<double, 2>{*lo, *hi};
}

template <Side Member>
std::string side_text(const C& o, const KeyInfo&) {
  const auto& side = o.*Member;
  return side ? cat("[", shortest((*side)[0]), ", ", shortest((*side)[1]), "]") : std::string("(scaled)");
}

CensusRow census_row(std::string_view key, KeyType type, Bounds bounds, std::string_view unit,
                     std::string_view meaning, std::string default_text, RowAccess<C> access) {
  return {{kCensus, key, type, bounds, {}, unit, meaning, {}, std::move(default_text), true}, access.read, access.text, {}};
}

constexpr const char* kCoordinates[4] = {"x1", "x2", "v1", "v2"};
constexpr std::string_view kShockOnForm = "a non-empty array of distinct names among \"x1\", \"x2\", \"v1\", \"v2\"";

void read_shock_on(C& o, const KeyInfo&, const toml::node& node, const std::string& loc) {
  const toml::array* a = node.as_array();
  std::array<bool, 4> on = {false, false, false, false};
  bool ok = a != nullptr && !a->empty();
  for (std::size_t i = 0; ok && i < a->size(); ++i) {
    const std::optional<std::string_view> name = a->get(i)->value<std::string_view>();
    const auto* at = name ? std::find(std::begin(kCoordinates), std::end(kCoordinates), *name) : std::end(kCoordinates);
    ok = at != std::end(kCoordinates) && !on[static_cast<std::size_t>(at - std::begin(kCoordinates))];
    if (ok) on[static_cast<std::size_t>(at - std::begin(kCoordinates))] = true;
  }
  if (!ok) fail(cat(loc, ": must be ", kShockOnForm));
  o.shock_on = on;
}

std::string shock_on_text(const C& o, const KeyInfo&) {
  std::string text;
  for (std::size_t i = 0; i < 4; ++i)
    if (o.shock_on[i]) text += cat(text.empty() ? "[" : ", ", "\"", kCoordinates[i], "\"");
  return text + "]";
}

// A numeric option: its row is the key table's (option_keys(), core/model/keys.hpp).
CensusRow numeric_row(std::string_view key, std::string default_text, RowAccess<C> access) {
  KeyInfo info = option_key(cat(kCensus, ".", key));
  info.default_text = std::move(default_text);
  return {std::move(info), access.read, access.text, {}};
}

// A side of the box of initial states: over the [initial] key of its name, in that key's unit.
template <Side Member>
CensusRow side_row(std::string_view key, std::string_view meaning) {
  const std::string_view unit = Key::at(cat("initial.", key)).info().unit;
  CensusRow r = census_row(key, KeyType::real, Bounds::finite(), unit, meaning, "(scaled)",
                           {read_side<Member>, side_text<Member>});
  r.allowed_text = "[lo, hi], lo <= hi, hi - lo finite";
  r.info.default_given = false;
  return r;
}

// The minimal critical shock's rows (core/analysis/census/critical_shock.hpp).
void add_shock_rows(std::vector<CensusRow>& rows) {
  const C d;
  rows.push_back(census_row("shock", KeyType::boolean, Bounds::finite(), "-",
                            "also find each listed periodic attractor's minimal critical shock: the smallest "
                            "perturbation of one of its period-start states, in motion scales, that sends the motion "
                            "to another attractor (run --census --shock; a census map's /attractor_shock)",
                            d.shock ? "true" : "false", bool_field<C, &C::shock>()));
  CensusRow on = census_row("shock_on", KeyType::choice, Bounds::finite(), "-",
                            "shock: the coordinates the shock moves (the others stay 0); [\"v1\", \"v2\"]: a "
                            "velocity kick, the impulse a blow gives",
                            shock_on_text(d, {}), {read_shock_on, shock_on_text});
  on.allowed_text = "distinct names among \"x1\", \"x2\", \"v1\", \"v2\", at least one";
  rows.push_back(on);
  rows.push_back(numeric_row("shock_directions", std::to_string(d.shock_directions),
                             integer_field<C, &C::shock_directions>()));
  rows.push_back(numeric_row("shock_tolerance", float_text(d.shock_tolerance), real_field<C, &C::shock_tolerance>()));
  rows.push_back(numeric_row("shock_max_radius", float_text(d.shock_max_radius), real_field<C, &C::shock_max_radius>()));
  rows.push_back(census_row("shock_optimise", KeyType::boolean, Bounds::finite(), "-",
                            "shock: refine the best random direction by the compass search on the sphere; false: the "
                            "random directions alone (for checks)",
                            d.shock_optimise ? "true" : "false", bool_field<C, &C::shock_optimise>()));
  rows.push_back(census_row("shock_soft_only", KeyType::boolean, Bounds::finite(), "-",
                            "shock: search only the soft attractors (the question of a soft-impact machine: how hard "
                            "a kick knocks the soft motion out); the others report not_computed",
                            d.shock_soft_only ? "true" : "false", bool_field<C, &C::shock_soft_only>()));
}

std::vector<CensusRow> make_rows() {
  const C d;
  std::vector<CensusRow> rows;
  rows.push_back(numeric_row("initial_conditions", std::to_string(d.initial_conditions),
                             integer_field<C, &C::initial_conditions>()));
  rows.push_back(side_row<&C::x1>("x1", "box side of x1; not given: the rest value +- L, L = max(D, lambda F0 / k1)"));
  rows.push_back(side_row<&C::x2>("x2", "box side of x2; not given: D +- L"));
  rows.push_back(side_row<&C::v1>("v1", "box side of v1; not given: +- omega L"));
  rows.push_back(side_row<&C::v2>("v2", "box side of v2; not given: +- omega L"));
  rows.push_back(numeric_row("seed", std::to_string(d.seed), integer_field<C, &C::seed>()));
  rows.push_back(numeric_row("max_attractors", std::to_string(d.max_attractors), integer_field<C, &C::max_attractors>()));
  rows.push_back(numeric_row("recurrences", std::to_string(d.recurrences), integer_field<C, &C::recurrences>()));
  rows.push_back(numeric_row("max_transient_periods", std::to_string(d.max_transient_periods),
                             integer_field<C, &C::max_transient_periods>()));
  rows.push_back(census_row("decide_by_recurrence", KeyType::boolean, Bounds::finite(), "-",
                            "a stay labels the state with that attractor unless states were seen to leave it "
                            "(Attractors.jl's rule; faster, but on transient chaos it keeps states brute force sees "
                            "leave before analysis.max_periods); false: non-periodic only at the budget's end, as "
                            "brute force",
                            d.decide_by_recurrence ? "true" : "false", bool_field<C, &C::decide_by_recurrence>()));
  rows.push_back(numeric_row("cell", float_text(d.cell), real_field<C, &C::cell>()));
  rows.push_back(numeric_row("rtol", float_text(d.rtol), real_field<C, &C::rtol>()));
  rows.push_back(census_row("early_stop", KeyType::boolean, Bounds::finite(), "-",
                            "decide states early (capture, Newton searches, recurrence when asked); false: brute force, every "
                            "state integrated to its steady state at [solver] rtol (for checks)",
                            d.early_stop ? "true" : "false", bool_field<C, &C::early_stop>()));
  add_shock_rows(rows);
  rows.push_back(numeric_row("family_distance", float_text(d.family_distance), real_field<C, &C::family_distance>()));
  rows.push_back(census_row("seed_from_neighbour", KeyType::boolean, Bounds::finite(), "-",
                            "census maps: each cell first follows one period-start state of each periodic attractor "
                            "of the cell before it along the last axis (not counted in the fractions: an attractor "
                            "only they reach has fraction 0); each such line is computed in order on one rank; "
                            "uniform maps only (sweep.refine = 0)",
                            d.seed_from_neighbour ? "true" : "false", bool_field<C, &C::seed_from_neighbour>()));
  return rows;
}

}  // namespace

const std::vector<CensusRow>& census_rows() {
  static const std::vector<CensusRow> rows = make_rows();
  return rows;
}

const std::vector<std::string_view>& census_keys() {
  static const std::vector<std::string_view> keys = [] {
    std::vector<std::string_view> k;
    for (const CensusRow& row : census_rows()) k.push_back(row.info.name);
    return k;
  }();
  return keys;
}

std::optional<CensusOptions> read_census(const toml::table& table, const Context& ctx) {
  const toml::table* sec = table.get_as<toml::table>(kCensus);
  if (sec == nullptr) return std::nullopt;
  CensusOptions o;
  read_rows(o, census_rows(), *sec, ctx);
  if (const std::string err = validate(o); !err.empty()) fail(cat(ctx.path, ": [census] ", err));
  return o;
}

// The shock's keys change no cell unless census.shock is on, and seed_from_neighbour none while it
// is off: then they are left out, so that a map's identity is the one it had before they existed.
std::vector<std::string> census_lines(const CensusOptions& o) {
  std::vector<std::string> lines = row_lines(kCensus, o, census_rows());
  if (!o.shock)
    std::erase_if(lines, [](const std::string& line) { return line.starts_with(cat(kCensus, ".shock")); });
  if (!o.seed_from_neighbour)
    std::erase_if(lines, [](const std::string& line) { return line.starts_with(cat(kCensus, ".seed_from_neighbour")); });
  return lines;
}

}  // namespace vibromap::detail
