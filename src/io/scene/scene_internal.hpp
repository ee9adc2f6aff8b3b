#pragma once
// Shared internals of the scene folder (src/io/scene/): the schema's bindings (keys.cpp),
// the sections and their keys (sections.cpp), TOML text helpers (toml_text.cpp), the
// reader's context and checked value reading (reader.cpp), and the [sweep] and [optimise]
// sections' readers and documentation rows (sweep_axes.cpp, sweep_section.cpp,
// optimise_section.cpp). Not installed; only the files of this folder include it.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "vibromap/io/scene/keys.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap::detail {

// ---------------------------------------------------------------------------------------
// The schema (keys.cpp).

// A checked value of one key: `real` for real and integer keys, `integer` for integer
// keys, `choice` (index into SceneKey::choices) for choice keys.
struct KeyValue {
  double real = 0.0;
  long long integer = 0;
  int choice = 0;
};

// How a key reads and writes its field of a parameter point. The reader applies every key it
// finds in schema order, [initial] last, so an [initial] key that fills the other components
// from the rest state (0, D, 0, 0) sees the final D; a [sweep] cell applies its axes the same
// way (cell_maker.cpp).
using Setter = void (*)(Parameters&, PointOptions&, const KeyValue&);
using Getter = std::optional<KeyValue> (*)(const Parameters&, const PointOptions&);  // nullopt: not set in this form

struct Accessors {
  Setter set;
  Getter get;
  long long int_max;   // integer keys: the largest value the field's type holds
  int component = -1;  // [initial] keys: the index into Parameters::initial (x1, x2, v1, v2)
};

// One row of the schema: the documentation view plus how to read and write the value.
struct Binding {
  SceneKey info;
  Accessors access;
  std::string_view unset_default;  // default_text when the default Scene does not set the key
};

// Every row, in schema order.
const std::vector<Binding>& bindings();
const Binding* find_binding(std::string_view section, std::string_view key);  // nullptr: none
// The row a name stands for: "section.key", or a key name only one section has ("omega").
// nullptr: no such key, or a name several sections have.
const Binding* find_key(std::string_view name);
std::size_t index_of(const Binding& b);  // its position in bindings()
std::string full_key(const SceneKey& k);  // "forcing.omega"
// How to give one key of a pair: "(k2 in N/m, or omega2 in rad/s)", "(xi1 dimensionless, or c1 in N s/m)".
std::string pair_advice(const SceneKey& a, const SceneKey& b);
bool is_numeric(const SceneKey& k);       // a real or integer key
// A choice key of [system], [contact] or [forcing] (contact.law): a [sweep] axis whose
// values are names, kept as indices into the key's choices.
bool is_categorical_axis(const SceneKey& k);
// A value of the key as a double: integer keys read it as a whole number.
KeyValue numeric_value(const SceneKey& k, double v);

// Bounds of numeric keys.
Bounds gt(double lo);          // > lo
Bounds ge(double lo);          // >= lo
Bounds any_finite();           // finite
Bounds interval(double lo, double hi, bool lo_open, bool hi_open);

// ---------------------------------------------------------------------------------------
// Sections and their keys (sections.cpp; the [sweep] and [optimise] lists in their own files).

inline constexpr std::string_view kSweep = "sweep";
inline constexpr std::string_view kOptimise = "optimise";

const std::vector<std::string_view>& sweep_option_keys();     // order, store, checkpoint_interval, progress_interval
const std::vector<std::string_view>& optimise_option_keys();  // objective, impact, ...
const std::vector<std::string_view>& optimise_keys();         // the free parameters, then the options
bool is_sweep_option(std::string_view key);  // one of sweep_option_keys()
// The first axes of the default order, by name: E1, E2, R1, R2, m2, k2, omega2.
std::vector<std::string_view> first_axes();

std::vector<std::string_view> schema_sections();  // the schema's sections, in order
std::vector<std::string_view> all_sections();     // the schema's, then [sweep], then [optimise]
bool is_section(std::string_view name);
std::vector<std::string_view> keys_of(std::string_view section);
bool has_key(std::string_view section, std::string_view key);
// The section that has a key of this name, if any ([sweep] and [optimise] for their options).
std::optional<std::string_view> section_of(std::string_view key);
// The other key of an either-or pair (omega2 for k2, also as free parameters of [optimise]),
// or empty. ([sweep] axes: sweep_section.cpp.)
std::string_view partner_of(std::string_view section, std::string_view key);
bool is_free_parameter(std::string_view name);  // free_parameter_names()
bool is_parameter_name(std::string_view name);  // variable_parameter_names()
// The schema row of a free parameter (its range and unit): E1 -> [contact] E1.
const SceneKey& free_parameter_key(std::string_view name);

// ---------------------------------------------------------------------------------------
// Text (toml_text.cpp).

std::string toml_float(double v);  // as shortest(), but always a TOML float ("1000.0")
std::string join(const std::vector<std::string_view>& items, std::string_view sep, std::string_view quote = {});
std::vector<std::string_view> views(const std::vector<std::string>& strings);
std::string unit_suffix(std::string_view unit);  // " (kg)"; empty for "-"
std::string trim(std::string_view s);            // without leading and trailing blanks
// The candidate closest to `name`, when it is close enough to be a likely typo.
std::optional<std::string_view> closest(std::string_view name, const std::vector<std::string_view>& candidates);
std::string toml_string(std::string_view s);  // a TOML basic string, quoted and escaped
std::string toml_key(std::string_view k);     // bare when it can be, else quoted
// A value as TOML text; floats in their shortest round-trip form, arrays and tables inline.
std::string node_text(const toml::node& node);
std::string clipped_text(const toml::node& node);  // node_text() clipped for a one-line message
std::string value_text(const SceneKey& k, const KeyValue& v);

// ---------------------------------------------------------------------------------------
// Reading (reader.cpp).

[[noreturn]] void fail(const std::string& message);  // throws SceneError

struct Context {
  std::string path;
  std::map<std::string, std::string, std::less<>> overrides;  // "section.key" -> "--set ..." as given
  std::vector<std::string> override_list;                     // in command-line order
};

std::string where(const Context& ctx, const toml::node& node);  // "file:3" (or "file")
// "file:3: [system] m2 = -5" or "file: --set system.m2=-5".
std::string locate(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node);
std::string locate(const Context& ctx, const SceneKey& k, const toml::node& node);
// Where a key comes from: "file:3", or "file: --set system.m2=-5".
std::string origin(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node);

std::optional<double> number_of(const toml::node& node);  // a TOML float or integer
// The checked value of a key of each type; `loc` (locate()) opens the message.
double read_real(const SceneKey& k, const toml::node& node, const std::string& loc);
int read_choice(const SceneKey& k, const toml::node& node, const std::string& loc);
long long read_boolean(const SceneKey& k, const toml::node& node, const std::string& loc);
// An array of strings; `what` says what they name.
std::vector<std::string> string_list(const toml::node& node, const std::string& loc, std::string_view what);

// ---------------------------------------------------------------------------------------
// [sweep] (sweep_section.cpp).

inline constexpr std::string_view kAxisForms = "{ from, to, n[, scale] } or { values[, scale] }";

// [sweep]'s scalar keys, documented as schema rows are, with the SweepOptions field each sets.
struct SweepInterval {
  SceneKey info;
  double SweepOptions::*field;
};
const std::vector<SweepInterval>& sweep_intervals();
// The refinement keys (sweep_refine.cpp): the rows of refine and refine_audit (refine_on is a
// list, documented by refine_on_meaning()); the reader (`census`: the scene has [census], which
// attractors and soft_fraction need); a refined map's identity lines (none when refine = 0).
const std::vector<SceneKey>& sweep_refine_keys();
std::string refine_on_list(const std::vector<RefineOn>& list);  // ["regime", "k_con:0.1"]
std::string refine_on_meaning();
void read_refine(const toml::table& sweep_table, const Context& ctx, bool census, SweepOptions& sweep);
std::vector<std::string> refine_lines(const SweepOptions& sweep);
const std::vector<std::string>& quantity_names();  // the storable quantities, in the table's order

double axis_end(const toml::table& axis, std::string_view field, const std::string& loc);  // a finite number
AxisScale axis_scale(const toml::table& axis, const std::string& loc);                      // "lin" by default

// One axis of a [sweep] table as the scene gives it.
struct SweepAxisEntry {
  std::string given;        // its name as given: "E1", "forcing.omega" (quoted or dotted)
  std::string text_key;     // the name as the scene text writes it: E1, "forcing.omega", forcing.omega
  const Binding* binding;   // the key it sweeps
  const toml::node* node;   // its table
};
// The axes of a [sweep] table in the default order (E1, E2, R1, R2, m2, k2, omega2, then the
// schema's order); fails on an unknown or non-numeric key, a key given twice, both keys of a
// pair, or more than kMaxSweepAxes axes.
std::vector<SweepAxisEntry> sweep_axis_entries(const toml::table& sweep, const Context& ctx);
// `--set sweep.NAME=...`: removes every spelling of NAME's key and of its pair partner from
// the [sweep] table, so that the override replaces them; fails as the file would on a bad NAME.
void erase_sweep_axis(toml::table& sweep, std::string_view name, const std::string& loc);
std::optional<SweepOptions> read_sweep(const toml::table& table, const Context& ctx);

// ---------------------------------------------------------------------------------------
// [optimise] (optimise_section.cpp).

inline constexpr std::string_view kVariableForm = "{ min, max[, scale] }";

// [optimise]'s keys other than the free parameters: the documentation row and how the key is
// read into OptimiseOptions.
template <class Options>
struct OptionRow {
  SceneKey info;
  void (*read)(Options&, const SceneKey&, const toml::node&, const std::string& loc);
  std::string (*text)(const Options&, const SceneKey&);  // the value read, canonical text
  std::string_view allowed_text = {};  // what is allowed, when info.allowed() cannot say it

  std::string allowed() const { return allowed_text.empty() ? info.allowed() : std::string(allowed_text); }
};
using OptimiseRow = OptionRow<OptimiseOptions>;
const std::vector<OptimiseRow>& optimise_rows();
// The canonical text of each [optimise] key of `o` (identity.cpp): "optimise.KEY = VALUE" lines.
std::vector<std::string> optimise_lines(const OptimiseOptions& o);
std::optional<OptimiseOptions> read_optimise(const toml::table& table, const Context& ctx);

// ---------------------------------------------------------------------------------------
// [census] (census_section.cpp): its rows read CensusOptions as [optimise]'s read theirs.

inline constexpr std::string_view kCensus = "census";
using CensusRow = OptionRow<CensusOptions>;
const std::vector<CensusRow>& census_rows();
const std::vector<std::string_view>& census_keys();
std::vector<std::string> census_lines(const CensusOptions& o);  // "census.KEY = VALUE"
std::optional<CensusOptions> read_census(const toml::table& table, const Context& ctx);

}  // namespace vibromap::detail
