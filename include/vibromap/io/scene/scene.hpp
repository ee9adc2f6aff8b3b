#pragma once
// Scenes: the TOML files that describe one parameter point and how to solve it, and, with
// their optional [sweep], [optimise] and [census] sections, a grid, an optimisation and a
// census. Every key, its range, unit and default is in docs/keys.md (`vibromap keys`), the
// sections are explained in docs/guide-run.md and the guides of each command; the keys of a
// point are declared once in the key table (core/model/keys.hpp).
//
// Contract: load_scene() either returns a Scene whose values all passed the key table's checks
// and validate(Parameters), or throws SceneError with one line naming the file (and line, or
// the --set option), the key, its value and what is allowed, e.g.
//   jobs/x.toml:3: [system] m2 = -5: must be > 0 (kg)
// Unknown sections and keys are errors (with a "did you mean" hint), so a typo never silently
// falls back to a default. Overrides ("section.key=value", `--set`) are applied to the parsed
// file before the checks, the value read as TOML (or, when it is not, as a string); an override
// of one key of a pair (k2 | omega2, ...), or of a [sweep] axis or [optimise] free parameter,
// replaces every spelling of it and of its partner. A scene file must be a regular file of at
// most kMaxSceneBytes, opened without blocking and never read past the cap.

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/core/analysis/census/census.hpp"
#include "vibromap/core/analysis/point/point_solver.hpp"
#include "vibromap/core/model/parameters.hpp"
#include "vibromap/core/optimise/optimise_options.hpp"
#include "vibromap/io/scene/sweep_section.hpp"

namespace vibromap {

// The largest scene file load_scene reads, bytes. A scene is a few kB (jobs/reference.toml, every
// key with a comment, is about 14 kB); the cap only keeps a wrong path from being read without end.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{4} << 20;
inline constexpr std::string_view kMaxSceneText = "4 MiB (4194304 bytes)";  // kMaxSceneBytes in messages
static_assert(kMaxSceneBytes == 4194304);

// A bad scene: malformed TOML, unknown section or key, wrong type, value out of range,
// both keys of a pair, unreadable file or malformed override. what() is one line.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One parameter point and the options to solve it, as read from a scene; with a [sweep]
// section, also the grid around it (params is then the base of every cell).
struct Scene {
  Parameters params;
  PointOptions options;
  std::optional<SweepOptions> sweep;  // nullopt: no [sweep] section (a single point)
  std::optional<OptimiseOptions> optimise;  // nullopt: no [optimise] section
  std::optional<CensusOptions> census;      // nullopt: no [census] section (`run --census` then uses the defaults)
  std::array<bool, 4> initial_given{};  // the [initial] keys given (x1, x2, v1, v2); the others
                                        // follow the rest state (0, D, 0, 0)
  std::string path;  // the scene file as named by the user
  std::string text;  // the scene after overrides as TOML (keys as given, key table order);
                     // parse_scene(text, path, {}, axes) with the command's axes gives this Scene
                     // back. For provenance.
};

// An axis a command adds to a scene's [sweep] (`continue --param`, `orbit-diagram --param`): the
// axis (make_axis: its values already checked against its key) and the option that gave it,
// which messages name ("--param omega").
struct CommandAxis {
  Axis axis;
  std::string option;
};

// The axis a command's option steps (`--param KEY`): KEY by its name alone or in full, a
// parameter key (Key::is_parameter) when `parameter_only` (continue), else any key that can be an
// axis (orbit-diagram); `values` checked against the key. `option` is the option as the
// messages name it ("--param omega"). Throws SceneError naming it:
//   --param m2: [system] m2 = -5: must be > 0 (kg)
CommandAxis command_axis(std::string option, std::string_view name, std::vector<double> values, AxisScale scale,
                         bool parameter_only);

// Reads, overrides and checks a scene file. Throws SceneError. With `axes`, each is an axis of
// the scene's [sweep] (one is made when the file has none), replacing the file's axis of the same
// key or of its pair partner, and the grid so made is checked as one the file gave would be (the
// rule that combines keys at its corners); the axes are the command's, not the file's, so the
// scene text does not hold them.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 const std::vector<CommandAxis>& axes = {});

// As load_scene, from TOML text; `path` only names the source in messages and Scene::path.
Scene parse_scene(std::string_view text, const std::string& path, const std::vector<std::string>& overrides = {},
                  const std::vector<CommandAxis>& axes = {});

}  // namespace vibromap
