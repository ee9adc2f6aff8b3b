// A basins run's output: see include/vibromap/io/basins_output.hpp.

#include "vibromap/io/basins_output.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <ostream>

#include "vibromap/core/text.hpp"
#include "vibromap/io/json_writer.hpp"

namespace vibromap {

namespace {

long count_label(const BasinsContent& c, int label) {
  return static_cast<long>(std::count(c.labels.begin(), c.labels.end(), label));
}

// The share of the plane the fractions are over (pixels followed / to follow), 1 for none to follow.
double fractions_cover(const BasinsCoverage& r) {
  return r.pixels_to_follow == 0 ? 1.0 : static_cast<double>(r.pixels_followed) / static_cast<double>(r.pixels_to_follow);
}

// "over 412 of 1024 pixels (40 %)": a stopped run's fractions are the pixels done so far's.
std::string fractions_line(const BasinsCoverage& r, const BasinsContent& c) {
  const std::uint64_t shown =
      r.pixels_followed < r.pixels_to_follow ? std::min<std::uint64_t>(100 * r.pixels_followed / r.pixels_to_follow, 99) : 100;
  return cat("over ", std::to_string(r.pixels_followed), " of ", std::to_string(r.pixels_to_follow), " pixels (",
             std::to_string(shown), " %)",
             r.pixels_to_follow < c.plane.pixels() ? ", overlap excluded" : "",
             r.pixels_followed < r.pixels_to_follow ? "; the rest are not computed yet" : "");
}

void write_attractor_json(JsonWriter& w, const Attractor& a) {
  w.begin_object()
      .field("regime", a.regime.label())
      .field("n", a.regime.n)
      .field("k", a.regime.k)
      .field("k_con", a.k_con)
      .field("T_con", a.T_con)
      .field("F_max", a.F_max)
      .field("max_floquet", a.max_floquet)
      .field("soft", a.soft)
      .field("pixels", a.count)
      .field("fraction", a.fraction);
  write_stable_json(w.key("stable"), a.stable).end_object();
}

void write_entropy_json(JsonWriter& w, const BasinEntropySummary& e) {
  w.begin_object()
      .field("box", e.box)
      .field("boxes", e.boxes)
      .field("boundary_boxes", e.boundary_boxes)
      .field("S_b", e.S_b)
      .field("S_bb", e.S_bb)
      .field("log2_test", to_string(e.verdict))
      .field("alpha", e.alpha)
      .field("dimension", e.dimension)
      .field("fit_eps_lo", e.eps_lo)
      .field("fit_eps_hi", e.eps_hi)
      .field("fit_scales", e.fit_scales)
      .field("fit_rms", e.fit_rms)
      .field("note", e.ok ? e.alpha_note : e.message);
  w.key("uncertain_fraction").begin_array();
  for (const double f : e.uncertain) w.value(f);
  w.end_array().end_object();
}

std::string log2_text(const BasinEntropySummary& e) {
  switch (e.verdict) {
    case BoundaryVerdict::no_boundary: return "no boundary box";
    case BoundaryVerdict::fractal: return "S_bb > ln 2 = 0.6931: the boundary is fractal";
    case BoundaryVerdict::not_shown: break;
  }
  return "S_bb <= ln 2 = 0.6931: proves nothing (S_bb > ln 2 would prove a fractal boundary)";
}

std::string uncertainty_text(const BasinEntropySummary& e) {
  if (!e.ok) return "not computed: " + e.message;
  if (e.fit_scales == 0) return "not fitted: " + e.alpha_note;
  return cat("alpha ", printf_number(e.alpha, "%.3f"), ", boundary dimension d = 2 - alpha = ",
             printf_number(e.dimension, "%.3f"), " (eps ", std::to_string(e.eps_lo), "..", std::to_string(e.eps_hi),
             " pixels, ", std::to_string(e.fit_scales), " scales, rms residual ", printf_number(e.fit_rms, "%.3g"), " in ln f)");
}

void write_entropy_table(std::ostream& out, const BasinEntropySummary& e) {
  out << "basin entropy  S_b " << printf_number(e.S_b, "%.4f") << ", S_bb " << printf_number(e.S_bb, "%.4f") << " (in "
      << e.box << " x " << e.box << " pixel boxes; " << e.boundary_boxes << " of " << e.boxes << " on the boundary)\n"
      << "log 2 test     " << log2_text(e) << "\n"
      << "uncertainty    " << uncertainty_text(e) << "\n";
}

}  // namespace

void write_basins_json(std::ostream& out, const FarmFigures& f, const BasinsContent& c, const BasinsCoverage& r,
                       const std::string& output) {
  JsonWriter w(out);
  w.begin_object()
      .field("output", output)
      .field("plane", c.plane.name())
      .field("pixels", f.items)
      .field("pixels_resumed", f.items_resumed)
      .field("pixels_computed", f.items_computed)
      .field("complete", f.complete)
      .field("ranks", f.ranks)
      .field("wall_s", f.wall_s)
      .field("pixels_per_s", f.items_per_s)
      .field("pixels_followed", r.pixels_followed)
      .field("pixels_to_follow", r.pixels_to_follow)
      .field("fractions_cover", fractions_cover(r))
      .field("stopped_by", f.stopped_by)
      .field("unresolved", count_label(c, kUnresolvedLabel))
      .field("unlisted", count_label(c, kUnlistedLabel))
      .field("overlap", count_label(c, kOverlapLabel));
  write_entropy_json(w.key("entropy"), c.entropy);
  w.key("attractors").begin_array();
  for (const Attractor& a : c.attractors) write_attractor_json(w, a);
  w.end_array().end_object();
  out << "\n";
}

void write_basins_table(std::ostream& out, const FarmFigures& f, const BasinsContent& c, const BasinsCoverage& r,
                        const std::string& output) {
  out << "basins         " << output << stopped_note(f) << "\n"
      << "plane          " << c.plane.name() << ", " << c.plane.axes[0].size() << " x " << c.plane.axes[1].size()
      << " pixels (" << f.items_resumed << " from the resumed file, " << f.items_computed << " computed now)\n"
      << "ranks          " << f.ranks << "\n"
      << "wall time      " << std::setprecision(4) << f.wall_s << " s, " << f.items_per_s << " pixels/s\n"
      << "unresolved     " << count_label(c, kUnresolvedLabel) << ", unlisted " << count_label(c, kUnlistedLabel)
      << ", overlap " << count_label(c, kOverlapLabel) << " pixels\n"
      << "fractions      " << fractions_line(r, c) << "\n";
  write_entropy_table(out, c.entropy);
  out << "\n"
      << "  #  regime          fraction    pixels   k_con       T_con (s)   F_max (N)   max|mu|   stable  soft\n";
  for (std::size_t i = 0; i < c.attractors.size(); ++i) {
    const Attractor& a = c.attractors[i];
    char line[256];
    std::snprintf(line, sizeof line, "%3zu  %-14s  %8.4f  %8d  %10.4g  %10.4g  %10.4g  %7.4f   %-6s  %s\n", i,
                  a.regime.label().c_str(), a.fraction, a.count, a.k_con, a.T_con, a.F_max, a.max_floquet,
                  a.stable == 1 ? "yes" : a.stable == 0 ? "no" : "?", a.soft ? "yes" : "");
    out << line;
  }
}

}  // namespace vibromap
