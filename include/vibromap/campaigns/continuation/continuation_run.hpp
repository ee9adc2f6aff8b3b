#pragma once
// The continuation campaign (`vibromap continue`): one process, no farm.
//   start     the motion from rest at KEY = from (analysis.steady); where that is not periodic,
//             the stable orbit shooting finds there (continuation follows orbits that exist,
//             reached from rest or not)
//   branches  pseudo-arclength continuation of that orbit to KEY = to, and of the doubled
//             branches born at its period doublings (core/analysis/continuation/continuation.hpp)
//   measure   every point's cycle measured as `run` measures an orbit (measure_orbit)
//   output    the branch file (io/branch_file.hpp), when asked
// The report (core/analysis/continuation/continuation_report.hpp) is printed by io/branch_output.hpp.

#include <string>
#include <vector>

#include "vibromap/core/analysis/continuation/continuation.hpp"
#include "vibromap/core/analysis/continuation/continuation_report.hpp"
#include "vibromap/core/grid.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {

struct ContinuationConfig {
  double from = 0.0, to = 0.0;  // the key's range (finite, different)
  double ds_max = 0.05;         // largest step along a branch (scaled arclength; --ds-max)
  int max_points = 5000;        // per branch (--max-points)
  int pd_depth = 1;             // period-doubling generations switched onto (0: none)
  std::string output;           // branch file (HDF5); empty: none
  bool overwrite = false;       // replace an existing branch file
};

// A stop signal (parallel/signals.hpp) ends a continuation before its next point: the branch (or
// curve) being followed ends there with stop "stopped by SIGTERM" (the signal's name), no
// further branch or curve is started, the points found are measured and written (-o) and
// report.stop_signal is set; the command then exits with ExitCode::stopped. A stop while the
// start orbit is solved (from rest, which may take long) throws the core's Cancelled instead:
// nothing was found, nothing is written.
// Names the signal in a stop reason: kStoppedOnRequest becomes "stopped by SIGTERM".
std::string name_stop_signal(std::string stop, int signal);

// How a key's values are continued: in ln(value) when both ends of its interval are positive
// and span a factor of 100 or more (moduli over decades: a step is then a fraction of the
// decades, not of the interval's length), else in the value itself. The engine sees
// u = engine(value); every reported value is physical(u), in the key's own units (exactly the
// interval's ends and the anchor at their u).
struct KeyScale {
  bool log = false;
  double from = 0.0, to = 0.0, anchor = 0.0;  // physical; anchor: the scene's value of a curve's Q
  double engine(double value) const;
  double physical(double u) const;
};
inline constexpr double kLogSpan = 100.0;  // to / from (either order) from which the key is continued in ln
KeyScale key_scale(double from, double to, double anchor);
// A report of continue_scaled, and curve points, mapped back to the key's own units.
void to_physical(ContinuationReport& report, const KeyScale& scale);

// run_continuation's branches in the engine's units of `scale` (no file written).
ContinuationReport continue_scaled(const Scene& scene, const Axis& axis, const ContinuationConfig& config,
                                   const KeyScale& scale);

// Writes the branch file of a report in the key's own units (io/branch_file.hpp).
void write_branch_file(const std::string& path, const Axis& axis, const ContinuationReport& report,
                       const std::string& scene_text);

// Follows the scene's orbit along `axis` (a numeric scene key, as a one-axis [sweep] names it)
// over [config.from, config.to] (in ln of the key when key_scale says so) and writes the branch file when config.output is set (checked
// before any solve). Throws SceneError (no periodic orbit at the start; bad --ds-max or
// --max-points) and IoError (the file).
ContinuationReport run_continuation(const Scene& scene, const Axis& axis, const ContinuationConfig& config);

}  // namespace vibromap
