#pragma once
// Shared internals of the scene folder (src/io/scene/), the TOML reader of the key table
// (core/model/keys.hpp): the sections and their keys (sections.cpp), TOML text helpers
// (toml_text.cpp), the reader's context and checked value reading (reader.cpp), and the
// [sweep], [optimise] and [census] sections' readers and documentation rows (sweep_axes.cpp,
// sweep_section.cpp, sweep_refine.cpp, optimise_section.cpp, census_section.cpp). Not installed;
// only the files of this folder include it.

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
// The point keys (core/model/keys.hpp) as a scene names them.

// The sections of the point keys, in table order.
std::vector<std::string_view> point_sections();
// How to give one key of a pair: "(k2 in N/m, or omega2 in rad/s)", "(xi1 dimensionless, or c1 in N s/m)".
std::string pair_advice(const KeyInfo& a, const KeyInfo& b);

// ---------------------------------------------------------------------------------------
// Sections and their keys (sections.cpp; the [sweep] and [optimise] lists in their own files).

inline constexpr std::string_view kSweep = "sweep";
inline constexpr std::string_view kOptimise = "optimise";

const std::vector<std::string_view>& sweep_option_keys();     // order, store, checkpoint_interval, progress_interval
const std::vector<std::string_view>& optimise_option_keys();  // objective, impact, ...
const std::vector<std::string_view>& optimise_keys();         // the parameter keys' names, then the options
bool is_optimise_option(std::string_view key);  // one of optimise_option_keys()
bool is_sweep_option(std::string_view key);  // one of sweep_option_keys()
// The first axes of the default order, by name: E1, E2, R1, R2, m2, k2, omega2.
std::vector<std::string_view> first_axes();
// A key's place in the default order of [sweep] axes and [optimise] free parameters: the first
// axes above, then the key table's order.
std::size_t key_rank(Key k);

std::vector<std::string_view> all_sections();  // the point keys', then [sweep], [optimise] and [census]
bool is_section(std::string_view name);
std::vector<std::string_view> keys_of(std::string_view section);
bool has_key(std::string_view section, std::string_view key);
// The section that has a key of this name, if any ([sweep] and [optimise] for their options).
std::optional<std::string_view> section_of(std::string_view key);
// The other key of an either-or pair (omega2 for k2, also as free parameters of [optimise]),
// or empty. ([sweep] axes: sweep_section.cpp.)
std::string_view partner_of(std::string_view section, std::string_view key);
// The parameter key (Key::is_parameter) a free variable of [optimise] names, by its name alone
// (E1, omega) or in full (forcing.omega); nullopt for any other name.
std::optional<Key> free_parameter(std::string_view name);
// Calls f(given, text_key, node) for every entry of a [sweep] or [optimise] table that names a
// key (`is_option` tells the section's options apart): each key but the options, and each key
// of a point section's table (TOML's dotted form forcing.omega = { ... }). `given` is the name
// ("E1", "forcing.omega"), `text_key` the name as the scene text writes it back.
void for_each_key_entry(const toml::table& section, bool (*is_option)(std::string_view),
                        const std::function<void(std::string, std::string, const toml::node&)>& f);

// ---------------------------------------------------------------------------------------
// Text (toml_text.cpp).

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

// ---------------------------------------------------------------------------------------
// Reading (reader.cpp).

[[noreturn]] void fail(const std::string& message);  // throws SceneError

struct Context {
  std::string path;
  std::map<std::string, std::string, std::less<>> overrides;  // "section.key" -> "--set ..." as given
  std::vector<std::string> override_list;                     // in command-line order
  std::vector<CommandAxis> axes;                              // a command's own [sweep] axes
};

std::string where(const Context& ctx, const toml::node& node);  // "file:3" (or "file")
// Where a key's value comes from: "file:3", or "file: --set system.m2=-5".
std::string origin(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node);
// A value in a message: a float in its shortest round-trip form ("-5", "1e-09"), else its TOML
// text clipped.
std::string value_text(const toml::node& node);
// Where a key's value comes from and the key with that value, as a refusal opens
// (KeyInfo::refusal): "file:3: [system] m2 = -5", "file: --set m2=-5: [system] m2 = -5".
std::string locate(const Context& ctx, std::string_view section, std::string_view key, const toml::node& node);
std::string locate(const Context& ctx, const KeyInfo& k, const toml::node& node);

std::optional<double> number_of(const toml::node& node);  // a TOML float or integer
// The checked value of a key of each type; `loc` (locate()) opens the message.
double read_real(const KeyInfo& k, const toml::node& node, const std::string& loc);
int read_choice(const KeyInfo& k, const toml::node& node, const std::string& loc);
long long read_boolean(const KeyInfo& k, const toml::node& node, const std::string& loc);
// An array of strings; `what` says what they name.
std::vector<std::string> string_list(const toml::node& node, const std::string& loc, std::string_view what);

// ---------------------------------------------------------------------------------------
// [sweep] (sweep_section.cpp).

inline constexpr std::string_view kAxisForms = "{ from, to, n[, scale] } or { values[, scale] }";

// [sweep]'s scalar keys, documented as the key table's rows are, with the SweepOptions field each sets.
struct SweepInterval {
  KeyInfo info;
  double SweepOptions::*field;
};
const std::vector<SweepInterval>& sweep_intervals();
// The refinement keys (sweep_refine.cpp): the rows of refine and refine_audit (refine_on is a
// list, documented by refine_on_meaning()); the reader (`census`: the scene has [census], which
// attractors and soft_fraction need); a refined map's identity lines (none when refine = 0).
const std::vector<KeyInfo>& sweep_refine_keys();
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
  Key key;                  // the key it sweeps
  const toml::node* node;   // its table
};
// The axes of a [sweep] table in the default order (E1, E2, R1, R2, m2, k2, omega2, then the
// key table's order); fails on an unknown or non-numeric key, a key given twice, both keys of a
// pair, or more than kMaxSweepAxes axes.
std::vector<SweepAxisEntry> sweep_axis_entries(const toml::table& sweep, const Context& ctx);
// Removes every entry of a [sweep] or [optimise] table that names `target` or its pair partner,
// in any spelling (for_each_key_entry), so that an override replaces them.
void erase_key_entries(toml::table& section, Key target, bool (*is_option)(std::string_view));
// `--set sweep.NAME=...`: erase_key_entries for NAME's key; fails as the file would on a bad NAME.
void erase_sweep_axis(toml::table& sweep, std::string_view name, const std::string& loc);
// The [sweep] section with the command's axes of ctx added (in the default order; `order` of the
// file, when given, must then name them too); nullopt when there is neither.
std::optional<SweepOptions> read_sweep(const toml::table& table, const Context& ctx);

// ---------------------------------------------------------------------------------------
// [optimise] (optimise_section.cpp).

inline constexpr std::string_view kVariableForm = "{ min, max[, scale] }";

// [optimise]'s keys other than the free parameters: the documentation row and how the key is
// read into OptimiseOptions.
template <class Options>
struct OptionRow {
  KeyInfo info;
  void (*read)(Options&, const KeyInfo&, const toml::node&, const std::string& loc);
  std::string (*text)(const Options&, const KeyInfo&);  // the value read, canonical text
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
