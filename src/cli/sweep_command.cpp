// `vibromap sweep`: a scene's [sweep] on all MPI ranks into one HDF5 map.

#include <filesystem>
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "vibromap/parallel/sweep_runner.hpp"

namespace vibromap::cli {
namespace {

std::string default_output(const std::string& scene_path) {
  return std::filesystem::path(scene_path).stem().string() + ".h5";
}

void print_report(std::ostream& out, const SweepReport& r, const std::string& output, const std::string& format) {
  const double rate = r.wall_s > 0 ? static_cast<double>(r.cells_computed) / r.wall_s : 0.0;
  if (format == "json") {
    JsonWriter w(out);
    w.begin_object()
        .field("output", output)
        .field("cells_total", r.cells_total)
        .field("cells_resumed", r.cells_resumed)
        .field("cells_computed", r.cells_computed)
        .field("ranks", r.ranks)
        .field("wall_s", r.wall_s)
        .field("cells_per_s", rate)
        .field("checkpoints", r.checkpoints)
        .field("checkpoint_s", r.checkpoint_s)
        .field("interrupted", r.interrupted)
        .field("requests", r.requests)
        .field("request_us", r.requests ? 1e6 * r.request_s / static_cast<double>(r.requests) : 0.0);
    w.key("regimes").begin_object();
    for (const auto& [label, count] : r.regimes) w.field(label, count);
    w.end_object().end_object();
    out << "\n";
    return;
  }
  out << "map            " << output << (r.interrupted ? "  (interrupted: resume with --resume)" : "") << "\n"
      << "cells          " << r.cells_total << " (" << r.cells_resumed << " from the resumed map, " << r.cells_computed
      << " computed now)\n"
      << "ranks          " << r.ranks << "\n"
      << "wall time      " << std::setprecision(4) << r.wall_s << " s, " << rate << " cells/s\n"
      << "checkpoints    " << r.checkpoints << " (" << r.checkpoint_s << " s writing)\n"
      << "regimes       ";
  for (const auto& [label, count] : r.regimes) out << " " << label << " " << count;
  out << "\n";
}

}  // namespace

int sweep_command(const SweepArgs& args, std::ostream& out) {
  const MpiSession mpi;
  Scene scene;
  try {
    scene = load_scene(args.scene, args.sets);
  } catch (const SceneError&) {
    if (mpi.rank() != 0) throw QuietExit{kExitUsage};  // every rank sees the same error; rank 0 says it
    throw;
  }
  SweepRunConfig config;
  config.output = args.output.empty() ? default_output(args.scene) : args.output;
  config.resume = args.resume;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const SweepReport report = run_sweep(scene, config);
  if (mpi.rank() != 0) return kExitOk;
  print_report(out, report, config.output, args.format);
  return report.interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace vibromap::cli
