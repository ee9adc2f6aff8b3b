#pragma once
// The scene's documentation, written from the key catalogue (keys.hpp) and the [sweep] and
// [optimise] sections' own tables: `vibromap keys`, the --help summary and the reference
// scene (jobs/reference.toml).

#include <iosfwd>

namespace vibromap {

// `vibromap keys`: every key with its default, unit, allowed values and meaning; the
// [sweep] keys and the [optimise] keys follow in tables of their own.
void write_scene_keys(std::ostream& os);
// A compact list of sections and keys (for --help); pairs shown as "k1|omega1".
void write_scene_key_summary(std::ostream& os);
// A scene giving every key its default with a comment (meaning, unit, allowed); keys
// without a plain default (the other form of a pair, [initial]) appear commented out, and
// so do an example [optimise] and an example [sweep] section (uncommented, each parses).
// jobs/reference.toml is this output.
void write_reference_scene(std::ostream& os);

}  // namespace vibromap
