// `vibromap basins`: the attractor of every initial state of a plane, on all MPI ranks, into one
// HDF5 file (the basins campaign); its summary is io/basins_output.hpp.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "commands.hpp"
#include "vibromap/campaigns/basins/basins_run.hpp"
#include "vibromap/campaigns/exit_status.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/basins_output.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/mpi_session.hpp"

namespace vibromap::cli {

// `vibromap basins SCENE --plane A,B --grid NxM [--at V=X]... [--entropy-box N] [-o FILE.h5] [--resume | --overwrite]`
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
  std::string entropy_box;        // side of the basin entropy's boxes, pixels; empty: entropy_box() picks it
  std::string format = "table";
};

// Labels every pixel of the plane with its attractor on all ranks and prints the attractors.
// Throws SceneError on bad options (before any MPI or file work). Returns the exit code.
int basins_command(const BasinsArgs& args, std::ostream& out);

namespace {

constexpr int kMinPoints = 2, kMaxPoints = 4096;  // points along each plane variable
constexpr const char* kVariables = "x1, x2, v1, v2";

std::string default_output(const std::string& scene_path) {
  return std::filesystem::path(scene_path).stem().string() + "_basins.h5";
}

int variable(const std::string& option, const std::string& value, std::string_view name) {
  const int i = state_index(name);
  if (i < 0)
    throw SceneError(cat(option, " ", value, ": unknown variable '", std::string(name), "' (allowed: ", kVariables, ")"));
  return i;
}

std::array<int, 2> parse_plane(const std::string& text) {
  const auto comma = text.find(',');
  if (comma == std::string::npos)
    throw SceneError(cat("--plane ", text, ": must be two variables A,B of ", kVariables, " (e.g. x1,v1)"));
  const std::array<int, 2> vars{variable("--plane", text, std::string_view(text).substr(0, comma)),
                                variable("--plane", text, std::string_view(text).substr(comma + 1))};
  if (vars[0] == vars[1]) throw SceneError(cat("--plane ", text, ": the two variables must differ (of ", kVariables, ")"));
  return vars;
}

int parse_points(const std::string& text, std::string_view part) {
  int n = 0;
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), n);
  if (ec != std::errc() || end != part.data() + part.size() || part.empty() || n < kMinPoints || n > kMaxPoints)
    throw SceneError(cat("--grid ", text, ": must be NxM with N and M whole numbers from ", std::to_string(kMinPoints),
                         " to ", std::to_string(kMaxPoints), " (e.g. 200x200)"));
  return n;
}

std::array<int, 2> parse_grid(const std::string& text) {
  const auto x = text.find('x');
  const std::string_view all(text);
  if (x == std::string::npos) return {parse_points(text, ""), 0};
  return {parse_points(text, all.substr(0, x)), parse_points(text, all.substr(x + 1))};
}

void parse_at(const std::string& text, BasinsSpec& spec) {
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw SceneError(cat("--at ", text, ": must be VARIABLE=VALUE with a variable of ", kVariables, " (e.g. x2=0.05)"));
  const int var = variable("--at", text, std::string_view(text).substr(0, eq));
  if (var == spec.vars[0] || var == spec.vars[1])
    throw SceneError(cat("--at ", text, ": ", std::string(kStateNames[static_cast<std::size_t>(var)]),
                         " is a plane variable; fix only the other two"));
  double value = 0.0;
  const std::string_view v = std::string_view(text).substr(eq + 1);
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
  if (ec != std::errc() || end != v.data() + v.size() || v.empty() || !std::isfinite(value))
    throw SceneError(cat("--at ", text, ": the value must be a finite number in m or m/s"));
  spec.at[var] = value;
}

BasinsSpec parse_spec(const BasinsArgs& args) {
  BasinsSpec spec;
  spec.vars = parse_plane(args.plane);
  spec.n = parse_grid(args.grid);
  for (const std::string& at : args.at) parse_at(at, spec);
  if (!(args.checkpoint > 0.0) || !std::isfinite(args.checkpoint))
    throw SceneError(cat("--checkpoint ", std::to_string(args.checkpoint), ": must be a positive number of seconds"));
  return spec;
}

// The box side: --entropy-box, checked against the grid, or by default BasinEntropyOptions's
// (5 pixels), cut to the grid's smaller side on a smaller grid.
int entropy_box(const BasinsArgs& args, const BasinsSpec& spec) {
  const int side = std::min(spec.n[0], spec.n[1]);
  if (args.entropy_box.empty()) return std::min(BasinEntropyOptions{}.box, side);
  const std::string& text = args.entropy_box;
  int box = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), box);
  if (ec != std::errc() || end != text.data() + text.size() || box < 1 || box > side)
    throw SceneError(cat("--entropy-box ", text, ": must be a whole number of pixels from 1 to the grid's smaller side (",
                         std::to_string(side), ")"));
  return box;
}

}  // namespace

int basins_command(const BasinsArgs& args, std::ostream& out) {
  const BasinsSpec spec = parse_spec(args);  // the same on every rank: no MPI needed to refuse it
  const int box = entropy_box(args, spec);
  std::optional<Scene> read = load_scene_before_mpi(args.scene, args.sets);
  const MpiSession mpi;
  const Scene scene = load_scene_everywhere(mpi, std::move(read), args.scene, args.sets);
  BasinsPlane plane;
  mpi.agree([&] {
    if (const std::string e = validate(scene.census.value_or(CensusOptions{})); !e.empty())
      throw SceneError(cat(args.scene, ": [census] ", e));
    if (const std::string e = census_box_error(scene.params, scene.census.value_or(CensusOptions{})); !e.empty())
      throw SceneError(cat(args.scene, ": ", e));
    if (const std::string e = census_method_error(scene.options.integrator); !e.empty())
      throw SceneError(cat(args.scene, ": ", e));
    plane = make_basins_plane(scene, spec);
  }, exit_status_of);
  if (mpi.rank() != 0) plane = make_basins_plane(scene, spec);
  BasinsRunConfig config;
  config.output = args.output.empty() ? default_output(args.scene) : args.output;
  config.resume = args.resume;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  config.checkpoint_interval = args.checkpoint;
  config.entropy.box = box;
  const BasinsReport report = run_basins(mpi, scene, plane, config);
  if (mpi.rank() != 0) return report.farm.stop_signal ? code(ExitCode::stopped) : code(ExitCode::ok);
  if (args.format == "json") {
    write_basins_json(out, farm_figures(report.farm), report.content, report.coverage, config.output);
  } else {
    write_basins_table(out, farm_figures(report.farm), report.content, report.coverage, config.output);
  }
  out.flush();
  return campaign_exit(report.farm, config.output, "pixels");
}

namespace {

std::string basins_footer() {
  return "A plane of initial states: the two --plane variables (of x1, x2, v1, v2: positions of the\n"
         "bodies in m, velocities in m/s) on an evenly spaced NxM grid (--grid, N along the first\n"
         "variable, 2..4096 each) spanning the scene's [census] box of each (census.x1 = [lo, hi], ...;\n"
         "by default the rest state +- the motion's scale, 'vibromap keys'); the other two variables\n"
         "are the rest state's (x1 = 0, x2 = D, v1 = v2 = 0) unless --at gives them (--at x2=0.06).\n"
         "Each pixel's state is followed to the attractor its motion settles into, as 'run --census'\n"
         "follows its initial states ([census] and [analysis] set the numerics): one follower per MPI\n"
         "rank keeps every attractor it found, so later pixels are decided early against them. A pixel\n"
         "with the bodies overlapping (x1 > x2) is not followed (label -3).\n\n"
         "FILE.h5 (CF-1.8, opens in xarray): label (the attractor index of each pixel; -1 unresolved,\n"
         "-2 unlisted, -3 overlap, -4 not computed), done, the two coordinates, and per attractor its\n"
         "regime, n, k, k_con, T_con, F_max, max_floquet, stable, soft, pixels, fraction and\n"
         "stroboscopic states. Attractors are numbered by pixel count, so the file does not depend on\n"
         "the number of ranks. postprocess/vibromap-post plot_basins FILE.h5 -o FILE.png draws it.\n\n"
         "The summary and the file give the basin entropy S_b and the boundary basin entropy S_bb\n"
         "(Daza et al. 2016: the plane cut into --entropy-box pixel boxes; unresolved and unlisted\n"
         "pixels are outcomes of their own, overlap pixels are left out), the log 2 test (S_bb > ln 2:\n"
         "the boundary is fractal; S_bb <= ln 2 proves nothing) and the uncertainty exponent alpha\n"
         "(boundary dimension 2 - alpha) where at least 3 scales fit: docs/model.md.\n\n"
         "The file is rewritten atomically every --checkpoint seconds; a run stopped (SIGINT, SIGTERM,\n"
         "SIGUSR1: exit code 3) or killed leaves the file of its last checkpoint, and --resume computes\n"
         "the rest. An existing FILE.h5 is replaced only with --overwrite.";
}

}  // namespace

Command declare_basins(CLI::App& app) {
  auto args = std::make_shared<BasinsArgs>();
  CLI::App* b = app.add_subcommand("basins", "Basins of attraction on a plane of initial states, on MPI ranks");
  add_scene_options(*b, args->scene, args->sets, "Scene file (TOML)");
  b->add_option("--plane", args->plane, "The two state variables of the plane (of x1, x2, v1, v2)")
      ->type_name("A,B")
      ->capture_default_str();
  b->add_option("--grid", args->grid, "Points along the first and the second plane variable (2..4096 each)")
      ->type_name("NxM")
      ->capture_default_str();
  b->add_option("--at", args->at, "Fix a variable outside the plane (repeatable; default: the rest state)")
      ->allow_extra_args(false)
      ->type_name("VAR=VALUE");
  add_output_option(*b, "-o,--output", args->output, "File to write (default: the scene's name with _basins.h5)");
  add_resume_options(*b, args->resume, args->overwrite, "Continue an existing file of the same run",
                     "Replace an existing file");
  b->add_option("--checkpoint", args->checkpoint, "Seconds between rewrites of the file")
      ->check(kNumber)
      ->type_name("SECONDS")
      ->capture_default_str();
  b->add_option("--entropy-box", args->entropy_box,
                "Side of the basin entropy's boxes, pixels (1..the grid's smaller side; default 5, or that side when smaller)")
      ->type_name("N");
  b->add_flag("-q,--quiet", args->quiet, "No progress lines");
  add_format_option(*b, args->format, "Summary on stdout: table or json");
  return {.app = b, .footer = basins_footer(), .topic = "the basin pictures", .campaign = always_campaign,
          .run = [args](std::ostream& out) { return basins_command(*args, out); }};
}

}  // namespace vibromap::cli
