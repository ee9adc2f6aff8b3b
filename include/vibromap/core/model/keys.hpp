#pragma once
// The key table: every key of a parameter point, once. A point is the model's Parameters and the
// solver's PointOptions; each of their fields a user can set is a key, named "section.name" as a
// scene names it ([system] m1 is "system.m1"), with its type, allowed values, unit, meaning and
// the accessor that reads and writes it. Everything that names a key uses this table and its
// handle, Key: the scene reader and `--set`, `vibromap keys` and docs/keys.md, sweep axes,
// optimisation's free variables, `continue --param/--param2`, the census box, and the library's
// own checks (validate(Parameters), validate(IntegratorOptions), validate(AnalysisOptions)),
// so a library caller and the command line are held to the same rules, message for message.
//
// Sections: [system], [contact], [forcing] (the model: Parameters), [solver] (the integrator),
// [analysis] (the point solver), [initial] (the initial state). The [sweep], [optimise] and
// [census] sections are not point keys: their numeric options are rows of option_keys() below,
// and io/scene reads every option.
//
// A refusal names the key, the value and what is allowed, in one form everywhere:
//   [system] m2 = -5: must be > 0 (kg)
// each channel putting where the value came from in front (a scene's line, a --set option, a
// sweep axis, a --param option).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/core/model/parameters.hpp"

namespace vibromap {

struct PointOptions;  // core/analysis/point/point_solver.hpp: IntegratorOptions and AnalysisOptions

enum class KeyType { real, integer, choice, boolean };

// The values a numeric key allows: an interval whose ends may be open or infinite; the value
// must be finite too.
struct Bounds {
  double lo;
  double hi;
  bool lo_open;
  bool hi_open;

  static Bounds above(double lo);     // > lo
  static Bounds at_least(double lo);  // >= lo
  static Bounds finite();             // any finite number
  static Bounds between(double lo, double hi, bool lo_open = false, bool hi_open = false);  // [lo, hi] by default

  bool contains(double v) const;
  std::string to_string() const;  // "> 0", ">= 1", "in (-1, 0.5)", "in [1, 64]", "finite"
};

// One key as a user sees it: section, name, type, allowed values, unit and meaning.
struct KeyInfo {
  std::string_view section;               // "system"
  std::string_view name;                  // "m1"
  KeyType type;                           // real (TOML float or integer), integer, choice (a name), boolean
  Bounds bounds;                          // numeric keys
  std::vector<std::string_view> choices;  // choice keys: the names allowed, in the order their index counts
  std::string_view unit;                  // SI unit, "-" when dimensionless
  std::string_view meaning;               // one line
  std::string_view partner = {};          // the other key of an either-or pair (k2 | omega2), or empty
  std::string default_text = {};          // the default as a scene writes it ("1000.0", "\"hybrid\"", "true"), or
                                          // how it is derived when the default point leaves the key to its
                                          // partner or unset ("m1*omega1^2")
  bool default_given = true;              // default_text is a value (not a derivation)
  bool frequency_rule = false;            // read by frequency_ratio_error (forcing against the natural frequencies)
  bool identity_at_default = true;        // false: a run's identity leaves the key out while it holds its default
                                          // (an option added after maps were made: they keep their identity)

  std::string full_name() const;    // "system.m1"
  std::string allowed() const;      // "> 0", "an integer in [1, 64]", "one of \"hybrid\", \"dopri5\", \"rk4\"", "true or false"
  std::string unit_suffix() const;  // " (kg)"; empty for "-"
  bool is_numeric() const;          // a real or integer key
  // A value as a scene writes it: a real in its shortest round-trip form as a float ("1000.0",
  // "1e-10"), an integer whole, a choice (index) as its quoted name, a boolean true or false.
  std::string scene_text(double v) const;
  // Empty when `v` is allowed, else what is required: "must be > 0 (kg)", "must be a finite
  // number > 0 (kg)", "must be an integer in [1, 64]", "must be at most 2147483647" (an integer
  // key whose field holds at most `int_max`). A choice key takes an index into `choices`, a
  // boolean key 0 or 1.
  std::string requirement(double v, long long int_max = std::numeric_limits<long long>::max()) const;
  // The refusal of a value given as `value_text` (what the user wrote, or the number) with the
  // requirement it breaks: "[system] m2 = -5: must be > 0 (kg)".
  std::string refusal(std::string_view value_text, std::string_view requirement) const;
};

// A handle to one row of the table (cheap to copy; compare with ==).
class Key {
 public:
  // Every key, in table order: the sections in the order above, the keys in the order of
  // `vibromap keys`.
  static const std::vector<Key>& all();
  // The key named `name`: "section.name", or a name only one section has ("omega", "m2").
  // nullopt: no such key, or a name several sections have (x1: [initial] and not only).
  static std::optional<Key> find(std::string_view name);
  // As find(), for a name known to be a key; throws std::invalid_argument otherwise.
  static Key at(std::string_view name);

  const KeyInfo& info() const;
  std::string full_name() const { return info().full_name(); }
  std::size_t index() const { return index_; }  // position in all()

  // What the key may be used as. A parameter is a real key of [system], [contact] or
  // [forcing]: a sweep axis, an optimisation's free variable, `continue --param/--param2`. An
  // axis is any numeric key, or the categorical contact law (its values are choice indices).
  bool is_parameter() const;
  bool is_axis() const;
  bool is_categorical() const;  // a choice key of [system], [contact] or [forcing]
  int component() const;        // [initial] keys: the index into the state (x1, x2, v1, v2); else -1
  long long int_max() const;    // integer keys: the largest value the field holds

  // KeyInfo::requirement with the field's int_max().
  std::string requirement(double v) const;
  // Empty when `v` is allowed, else the refusal "[system] m2 = -5: must be > 0 (kg)".
  std::string check(double v) const;

  // Sets the key's field as the scene reader does: k2 and omega2 (k1, omega1) replace the spring
  // in their own form, xi and c the damper, an integer key takes v as a whole number, a choice
  // key the choice at index v, a boolean key v != 0, and an [initial] component fills the
  // components not yet set from the rest state (0, D, 0, 0). Checks nothing (check() does).
  void set(Parameters& p, PointOptions& o, double v) const;
  // A key of Parameters only (every key but [solver] and [analysis]); throws std::logic_error
  // for another.
  void set(Parameters& p, double v) const;
  // The value as given in this form; nullopt when the point gives it by its partner (omega2 for
  // k2) or leaves it unset (damping, [initial]).
  std::optional<double> stored(const Parameters& p, const PointOptions& o) const;
  // The key's value at the point, derived when it is not given in this form: k2 from omega2,
  // xi1 from c1, damping from the law's calibration, [initial] from the rest state. A key of
  // Parameters only (throws std::logic_error for another).
  double value(const Parameters& p) const;

  friend bool operator==(Key a, Key b) { return a.index_ == b.index_; }

 private:
  explicit Key(std::size_t index) : index_(static_cast<std::uint16_t>(index)) {}
  std::uint16_t index_;
};

// The numeric options of the scene's other sections ([census], [optimise], [sweep]), declared
// here with the point keys so that each key's range is written once: io/scene reads them (their
// defaults are the options structs'), and the core's validate() of CensusOptions,
// OptimiseOptions and LocalOptions checks them by these rows. In section order, then key order.
const std::vector<KeyInfo>& option_keys();
// The row of an option named in full ("census.seed"); throws std::logic_error for another name.
const KeyInfo& option_key(std::string_view full_name);
// Empty when `v` is allowed for that option, else its refusal: "[census] seed = -1: must be an
// integer in [0, 9e+15]".
std::string check_option(std::string_view full_name, double v);

// Every refusal of the keys of `section` at the point (only the keys given in their own form),
// in table order.
std::vector<std::string> refusals(const Parameters& p, const PointOptions& o, std::string_view section);

// The refusal of a point at which a quantity derived from the keys `inputs` (full names) is
// out of its range, `ok(p)` false: `what` names the quantity and its unit ("the force amplitude
// lambda F0 (N)"), `fault` what is wrong with it ("not finite"). It names the input given in its own form that lies furthest from the
// default point among those whose default would make ok() hold, with the bound that key must
// keep, the other keys as given, found by bisection (the derived quantities are monotone in
// each key): "[forcing] lambda = 1.7976931348623157e+308: makes the force amplitude lambda F0
// (N) not finite; with the other keys as given it must be at most 3.59e+305". Empty when ok(p).
std::string derived_refusal(const Parameters& p, const std::vector<std::string_view>& inputs, std::string_view what,
                            const std::function<bool(const Parameters&)>& ok, std::string_view fault = "not finite");

// The text of a numeric value in a refusal: its shortest round-trip form ("-5", "1e-09").
std::string value_text(double v);

// An axis over `key` with these values (a categorical key: indices into its choices), named,
// united and described from the table. Throws std::invalid_argument with the refusal of the
// first value the key does not allow ("[system] m2 = -5: must be > 0 (kg)"), or with what is
// wrong with the axis itself (validate_axis); a key that cannot be an axis is a logic_error.
Axis make_axis(Key key, std::vector<double> values, AxisScale scale = AxisScale::lin);
// n points from `from` to `to` (axis_points).
Axis make_axis(Key key, double from, double to, int n, AxisScale scale = AxisScale::lin);

}  // namespace vibromap
