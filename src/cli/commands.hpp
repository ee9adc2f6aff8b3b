#pragma once
// The subcommands of the vibromap executable. main.cpp declares the command line (CLI11),
// parses it and dispatches here; every command returns the process exit code
// (parallel/exit_code.hpp) and lets its errors reach main, which prints them as one line and
// maps them to the exit code (campaigns/exit_status.hpp).

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/exit_code.hpp"

namespace vibromap {
class MpiSession;
struct Scene;
struct FarmReport;
}  // namespace vibromap

namespace vibromap::cli {

// Forcing periods kept by `run --trajectory` when the scene's [analysis] trajectory_periods is 0.
inline constexpr int kDefaultTrajectoryPeriods = 2;

// `vibromap run SCENE [--set section.key=value]... [--format table|json] [--trajectory FILE.h5]`
struct RunArgs {
  std::string scene;              // scene file (TOML)
  std::vector<std::string> sets;  // overrides "section.key=value", in command-line order
  std::string format = "table";   // "table" or "json"
  std::string trajectory;         // HDF5 file for the kept trajectory; empty: none
  bool overwrite = false;         // replace an existing trajectory file
  bool census = false;            // look for every attractor ([census]) instead of the one from rest
  bool labels = false;            // with census: also print each initial state and its attractor
};

// Solves the scene's point and prints its summary to `out`; writes the trajectory file when
// asked. Throws SceneError on a bad scene, IoError when a file cannot be written.
int run_command(const RunArgs& args, std::ostream& out);

// `vibromap sweep SCENE [--set section.key=value]... [--output FILE.h5] [--resume | --overwrite]`
// Collective under mpirun: every rank runs it; only rank 0 prints.
struct SweepArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string output;        // map file; empty: the scene's name with .h5, in the current directory
  bool resume = false;       // continue an existing map
  bool overwrite = false;    // replace an existing map
  bool quiet = false;        // no progress lines
  std::string format = "table";  // final summary: "table" or "json"
};

// Runs the sweep on all ranks. Returns the exit code (stopped when a signal stopped it, with
// a checkpoint written).
int sweep_command(const SweepArgs& args, std::ostream& out);

// `vibromap accuracy SCENE [--set section.key=value]... [--csv FILE.csv] [--format table|json]`
struct AccuracyArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string csv;               // CSV file of the rows; empty: none
  bool overwrite = false;        // replace an existing CSV file
  std::string format = "table";  // stdout: "table" or "json"
  bool quiet = false;            // no progress lines on stderr
};

// Solves the scene's point with every case of the default accuracy study (accuracy.hpp) and
// prints error against cost; writes the CSV when asked. Throws SceneError on a bad scene,
// IoError when the CSV cannot be written (checked before the solves, too).
int accuracy_command(const AccuracyArgs& args, std::ostream& out);

// `vibromap optimise SCENE [--set section.key=value]... [--output FILE.h5] [--resume | --overwrite]
// [--format table|json] [-q]`. Collective under mpirun: every rank runs it; only rank 0 prints.
struct OptimiseArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string output;            // result file; empty: the scene's name with _optimise.h5, in the current directory
  bool resume = false;           // finish a killed run from its journal FILE.h5.journal
  bool overwrite = false;        // replace an existing result file (and recompute the seeding sweep's map)
  bool quiet = false;            // no progress lines
  std::string format = "table";  // stdout: "table" or "json"
};

// The files of an optimisation with result file `output` (FILE.h5): the seeding sweep's map
// FILE_map.h5, the best point's trajectory FILE_trajectory.h5 and, while it runs, the journal of
// its finished starts FILE.h5.journal.
std::string optimise_map_path(const std::string& output);
std::string optimise_trajectory_path(const std::string& output);
std::string optimise_journal_path(const std::string& output);

// Runs the scene's [optimise] on all ranks and prints the starts and the best points.
// Returns the exit code (stopped when a signal stopped the seeding sweep or the starts, with
// the map or the journal checkpointed).
int optimise_command(const OptimiseArgs& args, std::ostream& out);

// A command that steps one scene key (`orbit-diagram`, `continue`): the scene loaded (by `load`,
// with `sets`) with the key's values as a one-axis [sweep] override `axis` (TOML, e.g.
// "{from=1,to=2,n=5}"), so that the key and its values are checked, and named with unit and
// meaning, exactly as a sweep axis; errors name --param instead of the override.
struct ParamScene {
  Scene scene;
  Axis axis;  // the stepped key's axis
};
using SceneLoader = std::function<Scene(const std::vector<std::string>& sets)>;
ParamScene scene_with_param(const SceneLoader& load, std::vector<std::string> sets, const std::string& param,
                            const std::string& axis);
std::string short_number(double x);  // 12 digits: 7.23, for messages
std::string exact_number(double x);  // 17 digits: the double itself, for overrides

// `vibromap continue SCENE --param KEY --from A --to B [--format table|json] [--set ...]`: the
// periodic orbit the scene's point settles into from rest at KEY = A, followed to B by
// pseudo-arclength continuation (core/analysis/continuation.hpp). One process.
struct ContinueArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string param;
  double from = 0.0, to = 0.0;
  double ds_max = 0.05;          // largest step along the branch (scaled arclength)
  int max_points = 5000;         // per branch
  int pd_depth = 1;              // period-doubling generations switched onto (0: none)
  std::string output;            // branch file (HDF5); empty: none
  bool overwrite = false;        // replace an existing branch file
  bool points = false;           // table: every point of every branch too (json always has them)
  std::string format = "table";
};
int continue_command(const ContinueArgs& args, std::ostream& out);

// `vibromap orbit-diagram SCENE --param KEY --from A --to B --steps N [--transient P] [--keep M]
// [-o FILE.h5] [--overwrite] [-q] [--format table|json] [--set section.key=value]...`.
// Collective under mpirun (the two directions run on two ranks); only rank 0 prints.
struct OrbitDiagramArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string param;             // the scene key to step ("forcing.omega", "omega", "contact.E2", ...)
  double from = 0.0, to = 0.0;   // its range, SI units, from < to
  int steps = 41;                // points from `from` to `to`, both included
  std::string scale = "lin";     // spacing of the points: lin or log
  long transient = 300;          // periods before the states are kept, at each point
  int keep = 16;                 // stroboscopic states kept at each point
  std::string output;            // HDF5 file; empty: none
  bool overwrite = false;
  bool quiet = false;
  std::string format = "table";
};
int orbit_diagram_command(const OrbitDiagramArgs& args, std::ostream& out);

// `vibromap basins SCENE --plane A,B --grid NxM [--at V=X]... [-o FILE.h5] [--resume | --overwrite]`
// Collective under mpirun: every rank runs it; only rank 0 prints.
struct BasinsArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string plane = "x1,v1";    // two of x1, x2, v1, v2
  std::string grid = "200x200";   // points along each plane variable
  std::vector<std::string> at;    // fixed values "x2=0.05" of the variables outside the plane
  std::string output;             // file; empty: the scene's name with _basins.h5, in the current directory
  bool resume = false;
  bool overwrite = false;
  bool quiet = false;
  double checkpoint = 30.0;       // s between rewrites of the file
  std::string format = "table";
};

// Labels every pixel of the plane with its attractor on all ranks and prints the attractors.
// Throws SceneError on bad options (before any MPI or file work). Returns the exit code.
int basins_command(const BasinsArgs& args, std::ostream& out);

// Rank 0, after a campaign's summary: ExitCode::ok, or (stopped by a signal) a line on stderr
// saying what `output` holds and that --resume goes on, and ExitCode::stopped.
int campaign_exit(const FarmReport& farm, const std::string& output, const char* noun);

// Rank 0 reads and checks the scene (its error ends every rank with one line from rank 0); the
// other ranks parse the text it read, so only rank 0 needs to see the file.
Scene load_scene_everywhere(const MpiSession& mpi, const std::string& path, const std::vector<std::string>& sets);

// `vibromap restitution [--law L]... [--e E]... [--format table|json]`: the effective restitution
// of a free two-body impact for each law (default: every dissipative law) and target e
// (default 0.1, 0.2, ..., 1). Throws SceneError for an unknown law or an e outside (0, 1].
struct RestitutionArgs {
  std::vector<std::string> laws;  // contact law names
  std::vector<double> e;          // target restitutions
  std::string format = "table";   // "table" or "json" (a list of {law, e, chi, e_effective})
};
int restitution_command(const RestitutionArgs& args, std::ostream& out);

// `vibromap keys [--toml]`: the scene schema as a table, or as a reference scene.
int keys_command(bool as_toml, std::ostream& out);

}  // namespace vibromap::cli
