#pragma once
// The scene's view of the key table (core/model/keys.hpp): the sections a scene has, a key's
// default as TOML text, and the `--set` overrides that name a point. The table itself, with
// every point key's type, range, unit, meaning and accessor, is the core's; the [sweep],
// [optimise] and [census] options are documented by their sections (docs.hpp).

#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/model/keys.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"

namespace vibromap {

// The point keys' sections in table order, then "sweep". ([optimise] and [census] come after
// "sweep" in messages, the scene text and the key summary.)
std::vector<std::string_view> scene_sections();

// "section.name=value" for `--set` that sets parameter key `k` to `value` in its shortest
// round-trip form as a TOML float, e.g. "contact.E1=20000.0" or "system.omega2=4.5529".
std::string parameter_override(Key k, double value);

// The `--set` overrides that reproduce an optimised point p: each free variable of o, and the
// contact law ("contact.law=flores") when o frees it.
std::vector<std::string> optimised_overrides(const Parameters& p, const OptimiseOptions& o);

}  // namespace vibromap
