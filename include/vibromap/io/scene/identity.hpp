#pragma once
// A run's identity from its parsed scene: the keys that define the results, one line each, in a
// canonical form, so that a resumed run can tell "the same run" from the scene's meaning, not
// its text (500 and 500.0, comments, key order and formatting never matter).

#include <string>
#include <string_view>
#include <vector>

#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

// Which keys define the run's results.
enum class IdentityScope {
  sweep,     // the point's keys, then [sweep]'s axes and store list (not its intervals)
  optimise,  // as sweep, then every [optimise] key
};

// One line "section.key = value" per key that defines a cell's result, sorted: every point key
// with its effective value (numbers in their shortest round-trip text; a pair under the key the
// scene holds it by, k2 or omega2; [initial] keys only where given); with a [sweep], its axes
// ("sweep.axis.D = KEY SCALE [v, ...]", D the axis's position) and store list, never
// checkpoint_interval or progress_interval; for IdentityScope::optimise, also each free
// parameter and option of [optimise] (all of them change the result), and, when
// min_soft_fraction > 0, the [census] options even when the scene leaves them to their defaults
// (the census of each point then defines the result). Ends with a newline.
std::string canonical_text(const Scene& scene, IdentityScope scope);

// One short entry per key whose line differs between two canonical texts, in key order, e.g.
// "system.m2 (100 in the file, 310 in the scene)" or "system.k2 (not in the file, 3187.6 in
// the scene)"; `recorded` is the file's, `current` the scene's. Long values are clipped.
std::vector<std::string> canonical_differences(std::string_view recorded, std::string_view current);

}  // namespace vibromap
