#pragma once
// Helpers shared by the commands of the vibromap executable (each declared by its own file,
// src/cli/<name>_command.cpp, and listed in registry.cpp). Every command returns the process
// exit code (parallel/exit_code.hpp) and lets its errors reach main, which prints them as one
// line and maps them to the exit code (campaigns/exit_status.hpp).

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/io/report.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/exit_code.hpp"

namespace vibromap {
class MpiSession;
struct Scene;
struct FarmReport;
}  // namespace vibromap

namespace vibromap::cli {

// The files of an optimisation with result file `output` (FILE.h5): the seeding sweep's map
// FILE_map.h5, the best point's trajectory FILE_trajectory.h5 and, while it runs, the journal of
// its finished starts FILE.h5.journal.
std::string optimise_map_path(const std::string& output);
std::string optimise_trajectory_path(const std::string& output);
std::string optimise_journal_path(const std::string& output);

// A command that steps scene keys (`orbit-diagram`, `continue`): the scene loaded (by `load`,
// with `sets`) with each stepped key's axis (command_axis: checked, and named with unit and
// meaning, exactly as a sweep axis) as a command axis of its [sweep].
struct ParamScene {
  Scene scene;
  Axis axis;  // the stepped key's axis
};
using SceneLoader = std::function<Scene(const std::vector<std::string>& sets, const std::vector<CommandAxis>& axes)>;
ParamScene scene_with_param(const SceneLoader& load, const std::vector<std::string>& sets, CommandAxis axis);
// The same with a second key (`continue --curve ... --param2`), which must be another key than
// the first (and not its pair partner).
struct ParamScene2 {
  Scene scene;
  Axis axis, axis2;
};
ParamScene2 scene_with_params(const SceneLoader& load, const std::vector<std::string>& sets, CommandAxis axis,
                              CommandAxis axis2);

// The farm's report as a campaign's summary prints it (io/report.hpp: io does not see the farm).
FarmFigures farm_figures(const FarmReport& farm);

// Rank 0, after a campaign's summary: ExitCode::ok, or (stopped by a signal) a line on stderr
// saying what `output` holds and that --resume goes on, and ExitCode::stopped.
int campaign_exit(const FarmReport& farm, const std::string& output, const char* noun);

// Rank 0 reads and checks the scene (its error ends every rank with one line from rank 0); the
// other ranks parse the text it read, so only rank 0 needs to see the file.
Scene load_scene_everywhere(const MpiSession& mpi, const std::string& path, const std::vector<std::string>& sets,
                            const std::vector<CommandAxis>& axes = {});

// Without an MPI launcher, the one process reads and checks the scene before MPI starts: a bad
// scene is refused at once, with no MPI to start (about a second) and finish for nothing. Under
// a launcher, nothing (std::nullopt: load_scene_everywhere reads it once MPI is up).
std::optional<Scene> load_scene_before_mpi(const std::string& path, const std::vector<std::string>& sets);
// The scene of a command that starts MPI: the one read before it, else load_scene_everywhere's.
Scene load_scene_everywhere(const MpiSession& mpi, std::optional<Scene> read_before, const std::string& path,
                            const std::vector<std::string>& sets);

}  // namespace vibromap::cli
