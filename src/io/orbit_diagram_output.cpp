// An orbit diagram's output: see include/vibromap/io/orbit_diagram_output.hpp.

#include "vibromap/io/orbit_diagram_output.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"

namespace vibromap {

namespace {

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

// A point's row: the key, then per direction the range of x1 and its distinct values.
void write_point_row(std::ostream& out, const OrbitDiagramData& d, std::size_t i) {
  out << "  " << std::setw(14) << std::setprecision(6) << d.axis.values[i];
  for (const auto* side : {&d.up, &d.down}) {
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

}  // namespace

void write_orbit_diagram_json(std::ostream& out, const FarmFigures& farm, const OrbitDiagramData& d,
                              const std::string& output) {
  JsonWriter w(out);
  w.begin_object().field("key", d.axis.key).field("output", output).field("wall_s", farm.wall_s);
  w.field("transient", d.options.transient).field("keep", d.options.keep);
  w.key("steps").begin_array();
  const std::size_t n = d.axis.values.size();
  for (int dir = 0; dir < 2; ++dir) {
    const auto& side = dir == 0 ? d.up : d.down;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = dir == 0 ? k : n - 1 - k;  // in the order the path was taken
      w.begin_object().field("param", d.axis.values[i]).field("direction", dir == 0 ? "up" : "down");
      w.field("status", to_string(side[i].status));
      write_strobe_x1_json(w, side[i].strobe).end_object();
    }
  }
  w.end_array().end_object();
  out << "\n";
}

void write_orbit_diagram_table(std::ostream& out, const FarmFigures& farm, const OrbitDiagramData& d,
                               const std::string& output) {
  const Axis& a = d.axis;
  out << "orbit diagram  " << a.key << " from " << number(a.values.front(), 12) << " to " << number(a.values.back(), 12)
      << " " << a.units << ", " << a.values.size() << " points, up and down\n"
      << "kept           " << d.options.keep << " stroboscopic states after " << d.options.transient
      << " periods at each point\n"
      << "wall time      " << std::setprecision(4) << farm.wall_s << " s on " << farm.ranks << " rank"
      << (farm.ranks > 1 ? "s" : "") << "\n";
  if (!output.empty()) out << "file           " << output << "\n";
  out << "\n  " << std::setw(14) << a.name << "   up: x1 (m) min..max  distinct   down: x1 (m) min..max  distinct\n";
  for (std::size_t i = 0; i < a.values.size(); ++i) write_point_row(out, d, i);
}

}  // namespace vibromap
