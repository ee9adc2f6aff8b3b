// `vibromap orbit-diagram`: see commands.hpp and include/vibromap/campaigns/orbit_diagram/.

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "commands.hpp"
#include "vibromap/campaigns/orbit_diagram/orbit_diagram_run.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"
#include "vibromap/parallel/mpi_session.hpp"

namespace vibromap::cli {
namespace {

void print_json(std::ostream& out, const OrbitDiagramReport& r, const OrbitDiagramArgs& args) {
  JsonWriter w(out);
  w.begin_object().field("key", r.data.axis.key).field("output", args.output).field("wall_s", r.farm.wall_s);
  w.field("transient", r.data.options.transient).field("keep", r.data.options.keep);
  w.key("steps").begin_array();
  const std::size_t n = r.data.axis.values.size();
  for (int d = 0; d < 2; ++d) {
    const auto& side = d == 0 ? r.data.up : r.data.down;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = d == 0 ? k : n - 1 - k;  // in the order the path was taken
      w.begin_object().field("param", r.data.axis.values[i]).field("direction", d == 0 ? "up" : "down");
      w.field("status", to_string(side[i].status));
      w.key("strobe_x1").begin_array();
      for (const Eigen::Vector4d& x : side[i].strobe) w.value(x[0]);
      w.end_array().end_object();
    }
  }
  w.end_array().end_object();
  out << "\n";
}

// Distinct kept x1 values at a point (within 1e-4 of the largest |x1|): 1 for a period-1 motion.
int branches(const DiagramStep& s) {
  double scale = 0.0;
  for (const Eigen::Vector4d& x : s.strobe) scale = std::max(scale, std::abs(x[0]));
  std::vector<double> seen;
  for (const Eigen::Vector4d& x : s.strobe) {
    bool known = false;
    for (double v : seen) known = known || std::abs(v - x[0]) <= 1e-4 * std::max(scale, 1e-12);
    if (!known) seen.push_back(x[0]);
  }
  return static_cast<int>(seen.size());
}

void print_table(std::ostream& out, const OrbitDiagramReport& r, const OrbitDiagramArgs& args) {
  const Axis& a = r.data.axis;
  out << "orbit diagram  " << a.key << " from " << short_number(a.values.front()) << " to " << short_number(a.values.back())
      << " " << a.units << ", " << a.values.size() << " points, up and down\n"
      << "kept           " << r.data.options.keep << " stroboscopic states after " << r.data.options.transient
      << " periods at each point\n"
      << "wall time      " << std::setprecision(4) << r.farm.wall_s << " s on " << r.farm.ranks << " rank"
      << (r.farm.ranks > 1 ? "s" : "") << "\n";
  if (!args.output.empty()) out << "file           " << args.output << "\n";
  out << "\n  " << std::setw(14) << a.name << "   up: x1 (m) min..max  distinct   down: x1 (m) min..max  distinct\n";
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    out << "  " << std::setw(14) << std::setprecision(6) << a.values[i];
    for (const auto* side : {&r.data.up, &r.data.down}) {
      const DiagramStep& s = (*side)[i];
      if (s.status != SolveStatus::ok) {
        out << "   " << std::setw(32) << "failed";
        continue;
      }
      double lo = s.strobe.front()[0], hi = lo;
      for (const Eigen::Vector4d& x : s.strobe) lo = std::min(lo, x[0]), hi = std::max(hi, x[0]);
      out << "   " << std::setw(11) << std::setprecision(5) << lo << " .. " << std::setw(11) << hi << std::setw(6)
          << branches(s);
    }
    out << "\n";
  }
}

}  // namespace

int orbit_diagram_command(const OrbitDiagramArgs& args, std::ostream& out) {
  const MpiSession mpi;
  if (!(std::isfinite(args.from) && std::isfinite(args.to) && args.from < args.to && std::isfinite(args.to - args.from)))
    throw SceneError(cat("--from ", short_number(args.from), " --to ", short_number(args.to),
                         ": need finite values with from < to and a finite to - from"));
  if (args.steps < 2 || args.steps > 1'000'000) throw SceneError("--steps must be in [2, 1000000]");
  OrbitDiagramConfig config;
  config.options.transient = args.transient;
  config.options.keep = args.keep;
  if (const std::string err = validate(config.options); !err.empty()) throw SceneError("--" + err);
  const ParamScene ps = scene_with_param(
      [&](const auto& sets) { return load_scene_everywhere(mpi, args.scene, sets); }, args.sets, args.param,
      cat("{from=", exact_number(args.from), ",to=", exact_number(args.to), ",n=", std::to_string(args.steps),
          ",scale=\"", args.scale, "\"}"));
  const Scene& scene = ps.scene;
  config.axis = ps.axis;
  config.output = args.output;
  config.overwrite = args.overwrite;
  config.progress = !args.quiet;
  const OrbitDiagramReport report = run_orbit_diagram(mpi, scene, config);
  if (mpi.rank() != 0) return report.farm.stop_signal ? code(ExitCode::stopped) : code(ExitCode::ok);
  if (!report.farm.complete()) return code(ExitCode::stopped);
  if (args.format == "json") {
    print_json(out, report, args);
  } else {
    print_table(out, report, args);
  }
  out.flush();
  return code(ExitCode::ok);
}

}  // namespace vibromap::cli
