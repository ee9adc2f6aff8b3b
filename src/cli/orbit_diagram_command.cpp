// `vibromap orbit-diagram`: the arguments and the exit; the campaign is
// include/vibromap/campaigns/orbit_diagram/, the output io/orbit_diagram_output.hpp.

#include <algorithm>
#include <cmath>
#include <memory>
#include <ostream>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/orbit_diagram/orbit_diagram_run.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/orbit_diagram_output.hpp"
#include "vibromap/parallel/mpi_session.hpp"

namespace vibromap::cli {

// `vibromap orbit-diagram SCENE --param KEY --from A --to B --steps N [--transient P] [--keep M]
// [-o FILE.h5] [--overwrite] [-q] [--format table|json] [--set section.key=value]...`.
// Collective under mpirun (the two directions run on two ranks); only rank 0 prints.
struct OrbitDiagramArgs {
  std::string scene;
  std::vector<std::string> sets;
  std::string param;             // the scene key to step ("forcing.omega", "omega", "contact.E2", ...)
  double from = 0.0, to = 0.0;   // the ends of its range, SI units, in either order
  int steps = 41;                // points between `from` and `to`, both included
  std::string scale = "lin";     // spacing of the points: lin or log
  long transient = 300;          // periods before the states are kept, at each point
  int keep = 16;                 // stroboscopic states kept at each point
  std::string output;            // HDF5 file; empty: none
  bool overwrite = false;
  bool quiet = false;
  std::string format = "table";
};
int orbit_diagram_command(const OrbitDiagramArgs& args, std::ostream& out);

int orbit_diagram_command(const OrbitDiagramArgs& args, std::ostream& out) {
  const MpiSession mpi;
  if (!(std::isfinite(args.from) && std::isfinite(args.to) && args.from != args.to && std::isfinite(args.to - args.from)))
    throw SceneError(cat("--from ", number(args.from, 12), " --to ", number(args.to, 12),
                         ": need finite, different values and a finite to - from"));
  // The same points whichever end comes first: the axis increases, and "up" is the key increasing.
  const double lo = std::min(args.from, args.to), hi = std::max(args.from, args.to);
  if (args.steps < 2 || args.steps > 1'000'000) throw SceneError("--steps must be in [2, 1000000]");
  OrbitDiagramConfig config;
  config.options.transient = args.transient;
  config.options.keep = args.keep;
  if (const std::string err = validate(config.options); !err.empty()) throw SceneError("--" + err);
  if (args.scale == "log" && !(lo > 0.0))
    throw SceneError(cat("--scale log: needs --from > 0 and --to > 0 (got ", number(lo, 12), ")"));
  const CommandAxis axis = command_axis(cat("--param ", clip(args.param)), args.param,
                                        axis_points(lo, hi, args.steps, parse_axis_scale(args.scale)),
                                        parse_axis_scale(args.scale), false);
  const ParamScene ps = scene_with_param(
      [&](const auto& sets, const auto& axes) { return load_scene_everywhere(mpi, args.scene, sets, axes); }, args.sets,
      axis);
  const Scene& scene = ps.scene;
  config.axis = ps.axis;
  config.output = args.output;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const OrbitDiagramReport report = run_orbit_diagram(mpi, scene, config);
  if (mpi.rank() != 0) return report.farm.stop_signal ? code(ExitCode::stopped) : code(ExitCode::ok);
  if (!report.farm.complete()) return code(ExitCode::stopped);
  if (args.format == "json") {
    write_orbit_diagram_json(out, farm_figures(report.farm), report.data, args.output);
  } else {
    write_orbit_diagram_table(out, farm_figures(report.farm), report.data, args.output);
  }
  out.flush();
  return code(ExitCode::ok);
}

namespace {

std::string orbit_diagram_footer() {
  return "The scene's point is stepped through N values of KEY between A and B (in either order: the\n"
         "points are the same), upwards (the key increasing) and downwards. Each direction starts\n"
         "from the scene's initial state (rest unless [initial] says otherwise) at its first point; at\n"
         "every next point the motion starts from the last state of the point before, so a branch is\n"
         "followed as far as it lives and the up and down sweeps differ where the response is\n"
         "multivalued (hysteresis). At each point TRANSIENT forcing periods are integrated, then KEEP\n"
         "stroboscopic states (at the period starts) are kept: one value for a period-1 motion, n for\n"
         "period n, a cloud for a chaotic one. The two directions run on two MPI ranks at once. KEY is\n"
         "checked as a [sweep] axis would be (vibromap keys). The table prints the range of x1 and the\n"
         "number of distinct x1 values per point and direction, the key increasing down the table;\n"
         "--format json prints steps (param, direction up or down, status, strobe_x1); -o writes every\n"
         "kept state (postprocess/vibromap-post plot_orbit_diagram FILE.h5 draws it).";
}

}  // namespace

Command declare_orbit_diagram(CLI::App& app) {
  auto args = std::make_shared<OrbitDiagramArgs>();
  CLI::App* od = app.add_subcommand("orbit-diagram",
                                    "Brute-force bifurcation diagram: step one key up and down, carrying the state");
  add_scene_options(*od, args->scene, args->sets, "Scene file (TOML)");
  od->add_option("-p,--param", args->param, "The scene key to step: forcing.omega, omega, contact.E2, m2, ...")
      ->required()
      ->type_name("KEY");
  od->add_option("--from", args->from, "One end of the key's range (SI units)")->check(kNumber)->required()->type_name("A");
  od->add_option("--to", args->to, "The other end (either side of A)")->check(kNumber)->required()->type_name("B");
  od->add_option("-n,--steps", args->steps, "Points between A and B, both included")->check(kNumber)->capture_default_str();
  od->add_option("--scale", args->scale, "Spacing of the points")
      ->check(CLI::IsMember({"lin", "log"}))
      ->type_name("lin|log")
      ->capture_default_str();
  od->add_option("--transient", args->transient, "Forcing periods integrated at each point before states are kept")
      ->check(kNumber)
      ->capture_default_str();
  od->add_option("--keep", args->keep, "Stroboscopic states kept at each point")->check(kNumber)->capture_default_str();
  add_output_option(*od, "-o,--output", args->output, "HDF5 file of the kept states (none by default)");
  od->add_flag("--overwrite", args->overwrite, "Replace an existing file");
  od->add_flag("-q,--quiet", args->quiet, "No progress lines");
  add_format_option(*od, args->format, "Output on stdout: table or json");
  return {.app = od, .footer = orbit_diagram_footer(), .topic = "the bifurcation diagram", .campaign = always_campaign,
          .run = [args](std::ostream& out) { return orbit_diagram_command(*args, out); }};
}

}  // namespace vibromap::cli
