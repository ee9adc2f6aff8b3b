#pragma once
// The key catalogue of scenes: every key of [system], [contact], [forcing], [solver],
// [analysis] and [initial] with its type, allowed range, unit, default and meaning. One
// table (src/io/scene/keys.cpp) drives parsing, validation, `vibromap keys`, the --help
// summary and the reference scene, so a key is added in one place. The [sweep] and
// [optimise] keys are not rows of it (an axis or a free parameter is a table, some options
// are arrays); their sections document them apart (docs.hpp).

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

enum class SceneKeyType { real, integer, choice, boolean };

// Allowed interval of a numeric key; infinite ends are unbounded. Values must be finite.
struct Bounds {
  double lo;
  double hi;
  bool lo_open;
  bool hi_open;
  bool contains(double v) const;
  std::string to_string() const;  // "> 0", ">= 1", "in (-1, 0.5)", "in [1, 64]"
};

// One key of the scene schema (documentation view).
struct SceneKey {
  std::string_view section;            // e.g. "system"
  std::string_view key;                // e.g. "m1"
  SceneKeyType type;                   // real (TOML float or integer), integer, choice (string), boolean (true/false)
  Bounds bounds;                       // numeric keys
  std::vector<std::string_view> choices;  // choice keys: the allowed strings
  std::string_view unit;               // SI unit, "-" when dimensionless
  std::string_view meaning;            // one line
  std::string_view partner;            // other key of an either-or pair, or empty
  std::string default_text;            // default as TOML text, or how it is derived
  bool default_given;                  // default_text is a TOML value (not a derivation)

  std::string allowed() const;         // "> 0", "one of \"hybrid\", \"dopri5\", \"rk4\"", "an integer in [1, 64]", "true or false"
};

// The schema, in documentation order (sections in order, keys in order within a section).
// The [sweep] and [optimise] keys are not in it (see the file comment).
const std::vector<SceneKey>& scene_keys();
// The section names in schema order, then "sweep". ([optimise] comes after "sweep" in
// messages, the scene text and the key summary.)
std::vector<std::string_view> scene_sections();

// "section.key=value" for `--set` that sets parameter `name` (E1, m2, omega2, ... as
// set_parameter names them), the value in its shortest round-trip form, e.g.
// "contact.E1=20000" or "system.omega2=4.5529". Throws std::invalid_argument when `name`
// is not a key of [system], [contact] or [forcing].
std::string parameter_override(std::string_view name, double value);

// The `--set` overrides that reproduce an optimised point p: each free variable of o, and the
// contact law ("contact.law=flores") when o frees it.
std::vector<std::string> optimised_overrides(const Parameters& p, const OptimiseOptions& o);

// Sets one numeric key of a parameter point exactly as the scene reader would: k2 and omega2
// (k1, omega1) replace the spring in their own form, xi and c the damper (a swept m2 keeps a
// given xi2 a ratio), integer keys take the value as an integer (it must be whole), and an
// [initial] component fills the components not yet set from the rest state (0, D, 0, 0).
using PointSetter = std::function<void(Parameters&, PointOptions&, double)>;
// The setter of a real or integer key named in full ("forcing.omega", "solver.rtol"), or of a
// categorical parameter key ("contact.law": the value is the index of the choice). Throws
// std::invalid_argument for an unknown key, a short name, another choice key or a boolean key.
PointSetter point_setter(std::string_view key);

}  // namespace vibromap
