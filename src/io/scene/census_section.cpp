// The [census] section of a scene: the options of CensusOptions, each a row like [optimise]'s.
// The box sides x1, x2, v1, v2 are arrays [lo, hi]; the others are numbers.

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
  rows.push_back(numeric_row("family_distance", float_text(d.family_distance), real_field<C, &C::family_distance>()));
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

std::vector<std::string> census_lines(const CensusOptions& o) {
  return row_lines(kCensus, o, census_rows());
}

}  // namespace vibromap::detail
