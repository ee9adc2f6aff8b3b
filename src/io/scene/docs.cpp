#include "vibromap/io/scene/docs.hpp"

#include <algorithm>
#include <array>
#include <ostream>

#include "vibromap/io/scene/keys.hpp"

#include "scene_internal.hpp"
#include "vibromap/core/text.hpp"

// The writers of the scene's documentation: tables for `vibromap keys`, the --help summary
// and the reference scene, from the key catalogue and the [sweep] and [optimise] rows.

namespace vibromap {

using detail::all_sections;
using detail::first_axes;
using detail::join;
using detail::keys_of;
using detail::kAxisForms;
using detail::kOptimise;
using detail::kSweep;
using detail::kVariableForm;
using detail::optimise_rows;
using detail::OptimiseRow;
using detail::partner_of;
using detail::quantity_names;
using detail::point_sections;
using detail::sweep_intervals;
using detail::SweepInterval;
using detail::unit_suffix;
using detail::views;

namespace {

std::string column(std::string_view s, std::size_t width) {
  std::string out(s);
  if (out.size() < width) out.append(width - out.size(), ' ');
  return out;
}

void write_reference_key(std::ostream& os, const KeyInfo& k) {
  std::string lhs = cat(k.name, " = ", k.default_text);
  if (!k.default_given) lhs = cat("# ", k.name, " = (", k.default_text, ")");
  os << column(lhs, 26) << "  # " << k.meaning << unit_suffix(k.unit) << ", " << k.allowed();
  if (!k.partner.empty()) os << "; or give " << k.partner;
  os << "\n";
}

// One row of `vibromap keys`.
struct KeyRow {
  std::string name, default_text, unit, allowed, meaning;
};

KeyRow key_row(const KeyInfo& k) {
  std::string meaning(k.meaning);
  if (!k.partner.empty()) meaning += cat("; or give ", k.partner);
  return {k.full_name(), k.default_text, std::string(k.unit), k.allowed(), meaning};
}

void write_key_table(std::ostream& os, const std::vector<KeyRow>& rows) {
  std::array<std::size_t, 4> w{3, 7, 4, 7};  // key, default, unit, allowed
  for (const KeyRow& r : rows) {
    w[0] = std::max(w[0], r.name.size());
    w[1] = std::max(w[1], r.default_text.size());
    w[2] = std::max(w[2], r.unit.size());
    w[3] = std::max(w[3], r.allowed.size());
  }
  os << column("key", w[0]) << "  " << column("default", w[1]) << "  " << column("unit", w[2]) << "  "
     << column("allowed", w[3]) << "  meaning\n";
  for (const KeyRow& r : rows) {
    os << column(r.name, w[0]) << "  " << column(r.default_text, w[1]) << "  " << column(r.unit, w[2]) << "  "
       << column(r.allowed, w[3]) << "  " << r.meaning << "\n";
  }
}

std::string store_text(const std::vector<Quantity>& store) {
  std::vector<std::string> names;
  for (const Quantity q : store) names.push_back(to_string(q));
  return cat("[", join(views(names), ", ", "\""), "]");
}

// The [sweep] rows of `vibromap keys`: the axes (any numeric key), then order, store and the
// intervals.
std::vector<KeyRow> sweep_rows() {
  std::vector<KeyRow> rows;
  rows.push_back({"sweep.KEY", "(not swept)", "KEY's", "values KEY allows",
                  cat("grid axis over any real or integer key above, named section.key (\"forcing.omega\" = ...) or "
                      "by the key alone when only one section has it (E1 = ...): ", kAxisForms,
                      ", scale \"lin\" or \"log\"; at most ", std::to_string(kMaxSweepAxes),
                      " axes, not both keys of a pair (k2|omega2, ...); integer keys take whole values; contact.law is a "
                      "categorical axis, { values = [\"hertz\", \"flores\", ...] }, kept in maps as the law's index")});
  rows.push_back({"sweep.order", cat("(", join(first_axes(), ", "), ", then key table order)"), "-",
                  "every axis once", "axis order, the first axis slowest in the flat cell index; by any name of each axis"});
  rows.push_back({"sweep.store", store_text(SweepOptions{}.store), "-", "quantity names",
                  cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", "),
                      " (status, regime, n, k, wall time and residual are always stored)")});
  for (const SweepInterval& row : sweep_intervals()) rows.push_back(key_row(row.info));
  rows.push_back(key_row(detail::sweep_refine_keys()[0]));
  rows.push_back({"sweep.refine_on", detail::refine_on_list(default_refine_on()), "-", "refine quantity names",
                  detail::refine_on_meaning()});
  rows.push_back(key_row(detail::sweep_refine_keys()[1]));
  rows.push_back(key_row(detail::sweep_refine_keys()[2]));
  return rows;
}

// The [optimise] rows of `vibromap keys`: the free parameters (any parameter key), then the options.
std::vector<KeyRow> optimise_doc_rows() {
  std::vector<KeyRow> rows;
  rows.push_back({"optimise.KEY", "(fixed)", "KEY's", "bounds KEY allows",
                  cat("free parameter and its box: any real key of [system], [contact] or [forcing], named by the key "
                      "alone (E1 = ...) or section.key (\"forcing.omega\" = ...): ", kVariableForm,
                      ", scale \"lin\" or \"log\"; not both keys of a pair (k2|omega2, ...)")});
  for (const OptimiseRow& row : optimise_rows()) {
    KeyRow r = key_row(row.info);
    r.allowed = row.allowed();
    rows.push_back(std::move(r));
  }
  return rows;
}

// The [census] rows of `vibromap keys`.
std::vector<KeyRow> census_doc_rows() {
  std::vector<KeyRow> rows;
  for (const detail::CensusRow& row : detail::census_rows()) {
    KeyRow r = key_row(row.info);
    r.allowed = row.allowed();
    rows.push_back(std::move(r));
  }
  return rows;
}

// One line of a commented example section: "# KEY = VALUE   # comment".
void write_example_line(std::ostream& os, const std::string& lhs, std::string_view comment) {
  os << "# " << column(lhs, 44) << "  # " << comment << "\n";
}

// A commented example [optimise] section: without the leading "# ", its lines parse.
void write_reference_optimise(std::ostream& os) {
  os << "\n# An optimisation for `vibromap optimise`: the values above are the base point and the free\n"
        "# parameters move inside their box (any real key of [system], [contact] or [forcing], as\n"
        "# NAME = { min, max[, scale] }, scale \"lin\" (default) or \"log\"). The starts are the best cells\n"
        "# of a map: `map`, or\n"
        "# the scene's [sweep] run first, or else the scene's point. [optimise] has no default: uncomment\n"
        "# and edit this example (jobs/paper/optimise_box.toml is a whole job).\n"
        "#\n"
        "# [optimise]\n"
        "# m2 = { min = 100.0, max = 310.0 }\n"
        "# E1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n";
  for (const OptimiseRow& row : optimise_rows()) {
    const KeyInfo& k = row.info;
    const std::string lhs = k.name == "map" ? std::string("map = \"box.h5\"") : cat(k.name, " = ", k.default_text);
    write_example_line(os, lhs, cat(k.meaning, unit_suffix(k.unit), ", ", row.allowed()));
  }
}

// A commented example [census] section: without the leading "# ", its lines parse.
void write_reference_census(std::ostream& os) {
  os << "\n# How `vibromap run --census` looks for every attractor of the point, with its basin fraction.\n"
        "# Every key is optional (a scene without [census] uses these defaults). In a sweep scene, a\n"
        "# [census] section runs the census in every cell (a census map: every attractor per cell).\n"
        "#\n"
        "# [census]\n";
  for (const detail::CensusRow& row : detail::census_rows()) {
    const KeyInfo& k = row.info;
    // The sides' examples are the defaults of Table 1 (L = D = 0.05 m, omega L = 0.3615 m/s).
    const std::string side = k.name == "x1" ? "[-0.05, 0.05]" : k.name == "x2" ? "[0.0, 0.1]" : "[-0.3615, 0.3615]";
    const std::string lhs = k.default_given ? cat(k.name, " = ", k.default_text) : cat(k.name, " = ", side);
    write_example_line(os, lhs, cat(k.meaning, unit_suffix(k.unit), ", ", row.allowed()));
  }
}

// A commented example [sweep] section: without the leading "# ", its lines parse.
void write_reference_sweep(std::ostream& os) {
  os << "\n# A grid for `vibromap sweep` over up to 8 of the real or integer keys above; a scene\n"
        "# without [sweep] is one point, and the values above are the base of every cell. [sweep] has\n"
        "# no default: uncomment and edit this example. An axis is named section.key, quoted or dotted\n"
        "# (\"forcing.omega\" = ... or forcing.omega = ...), or by the key alone when only one section\n"
        "# has it (E1, omega2, F0). It is { from, to, n[, scale] } (n points, ends exact, scale \"lin\"\n"
        "# (default) or \"log\") or { values = [...][, scale] }; its values must be allowed for its key\n"
        "# above (E1 > 0, ...; whole numbers for an integer key). Give k2 or omega2, not both (and so\n"
        "# for every pair).\n"
        "#\n"
        "# [sweep]\n"
        "# E1 = { from = 2e4, to = 2.1e11, n = 23, scale = \"log\" }\n"
        "# E2 = { values = [2e4, 1e6, 2.1e11] }\n";
  write_example_line(os, "order = [\"E1\", \"E2\"]",
       cat("axis order, first slowest; default ", join(first_axes(), ", "), ", then the order above"));
  write_example_line(os, cat("store = ", store_text(SweepOptions{}.store)),
       cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", ")));
  for (const SweepInterval& row : sweep_intervals()) {
    const KeyInfo& k = row.info;
    write_example_line(os, cat(k.name, " = ", k.default_text), cat(k.meaning, unit_suffix(k.unit), ", ", k.allowed()));
  }
  const auto& refine = detail::sweep_refine_keys();
  write_example_line(os, cat("refine = ", refine[0].default_text), cat(refine[0].meaning, ", ", refine[0].allowed()));
  write_example_line(os, cat("refine_on = ", detail::refine_on_list(default_refine_on())), detail::refine_on_meaning());
  write_example_line(os, cat("refine_audit = ", refine[1].default_text), cat(refine[1].meaning, ", ", refine[1].allowed()));
  write_example_line(os, cat("refine_speckle = ", refine[2].default_text), refine[2].meaning);
}

}  // namespace

// The rule that combines keys (parameters.hpp), under the key table and atop the reference scene.
std::string frequency_rule_text(std::string_view prefix) {
  static_assert(kMinFrequencyRatio == 1e-4 && kMaxFrequencyRatio == 1e4, "the text below states them");
  return cat(prefix, "Across keys: forcing.omega/omega_n must be in [1e-4, 1e4], omega_n the fastest natural\n",
             prefix, "frequency of m1 and m2 on their springs (k1|omega1, k2|omega2, no contact), and their\n",
             prefix, "fastest decay rate on the dampers (c1|xi1, c2|xi2) at most 1e4 forcing.omega; checked on\n",
             prefix, "the scene after --set and at every corner of a [sweep] grid and an [optimise] box.\n");
}

void write_scene_keys(std::ostream& os) {
  std::vector<KeyRow> rows;
  for (const Key k : Key::all()) rows.push_back(key_row(k.info()));
  write_key_table(os, rows);
  os << "\n" << frequency_rule_text("");
  os << "\n[sweep] (only in a sweep scene: a grid around the point above; example in jobs/reference.toml)\n";
  write_key_table(os, sweep_rows());
  os << "\n[optimise] (only in an optimisation scene: free parameters around the point above; example in "
        "jobs/reference.toml)\n";
  write_key_table(os, optimise_doc_rows());
  os << "\n[census] (how `vibromap run --census` looks for every attractor; every key optional; in a sweep scene "
        "it makes a census map)\n";
  write_key_table(os, census_doc_rows());
}

void write_scene_key_summary(std::ostream& os) {
  for (std::string_view section : all_sections()) {
    std::string line = cat("  ", column(cat("[", section, "]"), 11));
    if (section == kSweep) line += " KEY (an axis: any real or integer key above)";
    const auto keys = keys_of(section);
    for (const std::string_view key : keys) {
      const std::string_view partner = partner_of(section, key);
      const bool partner_first =
          !partner.empty() && std::find(keys.begin(), keys.end(), partner) < std::find(keys.begin(), keys.end(), key);
      if (partner_first) continue;
      line += cat(" ", key, partner.empty() ? "" : "|", partner);
    }
    os << line << "\n";
  }
}

void write_reference_scene(std::ostream& os) {
  os << "# vibromap reference scene: every key with its default value (SI units).\n"
        "# Generated by `vibromap keys --toml`; each line says what the key means and what\n"
        "# it allows. Commented-out keys have no plain default: the other form of a pair\n"
        "# (give k1 or omega1, xi1 or c1, ..., not both) and [initial], which defaults to\n"
        "# the rest state (x1, x2, v1, v2) = (0, D, 0, 0); set any subset of it.\n"
     << frequency_rule_text("# ");
  for (std::string_view section : point_sections()) {
    os << "\n[" << section << "]\n";
    for (const Key k : Key::all()) {
      if (k.info().section == section) write_reference_key(os, k.info());
    }
  }
  write_reference_optimise(os);
  write_reference_census(os);
  write_reference_sweep(os);
}

}  // namespace vibromap
