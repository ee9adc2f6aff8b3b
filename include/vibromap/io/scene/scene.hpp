#pragma once
// Scenes: the TOML files that describe one parameter point and how to solve it.
//
// A scene has the sections [system], [contact], [forcing], [solver], [analysis] and
// [initial]; every key is optional and defaults to the struct defaults of Parameters,
// IntegratorOptions and AnalysisOptions (the paper's Table 1 calibrated as docs/model.md says). All
// values are in SI units. One schema table (keys.hpp) lists every key with its type,
// allowed range, unit and meaning; it drives parsing, validation, `vibromap keys`,
// `vibromap run --help` and the reference scene (docs.hpp, jobs/reference.toml), so a key
// is added in one place.
//
// Contract: load_scene() either returns a Scene whose values all passed the schema's
// checks and validate(Parameters), or throws SceneError with a one-line message naming the
// file, the key, its value and what is allowed, e.g.
//   jobs/x.toml:3: [system] m2 = -5: must be > 0 (kg)
// Unknown sections and keys are errors (with a "did you mean" hint), so a typo never
// silently falls back to a default.
//
// A scene file must be a regular file of at most kMaxSceneBytes (4 MiB): a directory, a FIFO,
// a device (/dev/zero, /dev/urandom) or a bigger file is refused at once, before anything is
// read, and no more than the cap is ever read (the file is opened without blocking, so a FIFO
// never stalls the reader).
//
// Overrides ("section.key=value", from `--set`) are applied to the parsed file before the
// checks, with the value read as a TOML value (or, when it is not one, as a string). An
// override of one key of an either-or pair (k1 | omega1, k2 | omega2, xi1 | c1, xi2 | c2)
// replaces whichever of the pair the file gave; giving both in the file is an error.
//
// An optional [sweep] section makes the scene a grid (the values above are then the base of
// every cell; a swept key replaces the base value as --set would, so a swept k2 or omega2
// replaces the scene's spring2 in its own form, and a given xi2 stays a ratio):
//   [sweep]
//   E1 = { from = 2e4, to = 2.1e11, n = 23, scale = "log" }  # n points, ends exact; scale "lin" default
//   E2 = { values = [2e4, 1e6, 2.1e11] }                     # explicit points
//   "forcing.omega" = { from = 5.0, to = 9.0, n = 41 }       # any numeric key, by its full name
//   order = ["E1", "E2", "omega"]  # first axis slowest; default E1, E2, R1, R2, m2, k2, omega2,
//                                  # then the schema's order
//   store = ["T_con", "k_con"]   # optional quantities (core/quantities.hpp); default SweepOptions'
//   checkpoint_interval = 60.0   # s, > 0
//   progress_interval = 10.0     # s, > 0
// An axis is any real or integer key of [system] ... [initial], named in full ("forcing.omega",
// also as TOML's dotted key forcing.omega = {...}) or by the key alone when only one section
// has it (E1, omega2, F0, omega). Every axis value must lie in the range of the key (E1 > 0,
// ...); an integer key's values must be integers. At most kMaxSweepAxes axes, never both keys
// of a pair (k2 | omega2, ...) nor one key twice; choice and boolean keys cannot be axes.
// [sweep]'s keys are not rows of scene_keys() (an axis is a table, order and store are
// arrays); write_scene_keys documents them apart. `--set sweep.checkpoint_interval=5`,
// `--set 'sweep.E1={from=1e5,to=1e9,n=5}'` and `--set 'sweep.forcing.omega={values=[6,7]}'`
// work; an axis set so replaces every spelling of its key and of its pair partner.
//
// An optional [optimise] section makes the scene an optimisation (`vibromap optimise`,
// optimise_options.hpp): the values above are the base point, the free parameters move.
//   [optimise]
//   m2 = { min = 100, max = 310 }                          # a free parameter and its box; scale "lin" default
//   E1 = { min = 2e4, max = 2.1e11, scale = "log" }        # any of E1, E2, R1, R2, m2, k2|omega2
//   objective = "min_k_con"        # or "max_T_con" (with impact = i), "min_F_max"
//   regime = "(1,1)"               # kept as a constraint; "any": any motion with an impact
//   stability = "if_known"         # or "required", "ignored"
//   algorithm = ["bobyqa", "gradient_projection"]   # one name or a list: each seed with each
//   seeds = 4                      # the best cells of the seeding map
//   map = "box.h5"                 # seeding map; not given: the scene's [sweep] runs first,
//                                  # and without [sweep] the scene's point is the one seed
//   xtol_rel, ftol_rel, max_evaluations, max_time, initial_step, fd_step, barrier, best, verify_rtol
//   min_soft_fraction = 0.9        # robust softness: soft attractors hold >= 90 % of the basin (a
//                                  # census per point with [census]'s options; 0: off)
//   soft_check_initial_conditions = 512   # the best points' re-check census
// A free parameter's bounds must lie in the range of the parameter's own key; k2 and omega2
// may not both be free. Like [sweep], its keys are not rows of scene_keys(); write_scene_keys
// documents them apart, and they take --set (`--set optimise.algorithm=cobyla`,
// `--set 'optimise.E1={min=1e5,max=1e9,scale="log"}'`).
//
// An optional [census] section sets how `vibromap run --census` (and a sweep with census, and
// [optimise] min_soft_fraction) looks for every attractor of a point (census.hpp):
//   [census]
//   initial_conditions = 32       # K, the rest state included
//   x1 = [-0.05, 0.05]            # box of initial states, [lo, hi] in m (x1, x2) and m/s (v1, v2);
//                                 # not given: the rest state +- the motion's scale
//   seed = 1
//   max_attractors = 8
//                                 # (soft is one definition for all: analysis.soft_kcon)
//   recurrences, cell, rtol       # the census's numerics (vibromap keys)

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
