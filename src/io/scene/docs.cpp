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
using detail::axis_key;
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
using detail::schema_sections;
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

void write_reference_key(std::ostream& os, const SceneKey& k) {
  std::string lhs = cat(k.key, " = ", k.default_text);
  if (!k.default_given) lhs = cat("# ", k.key, " = (", k.default_text, ")");
  os << column(lhs, 26) << "  # " << k.meaning << unit_suffix(k.unit) << ", " << k.allowed();
  if (!k.partner.empty()) os << "; or give " << k.partner;
  os << "\n";
}

// One row of `vibromap keys`.
struct KeyRow {
  std::string name, default_text, unit, allowed, meaning;
};

KeyRow key_row(const SceneKey& k) {
  std::string meaning(k.meaning);
  if (!k.partner.empty()) meaning += cat("; or give ", k.partner);
  return {cat(k.section, ".", k.key), k.default_text, std::string(k.unit), k.allowed(), meaning};
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

// The [sweep] rows of `vibromap keys`: one per axis, then order, store and the intervals.
std::vector<KeyRow> sweep_rows() {
  std::vector<KeyRow> rows;
  for (const std::string_view name : sweep_axis_names()) {
    const SceneKey& k = axis_key(name);
    std::string meaning = cat("grid axis over [", k.section, "] ", name, ": ", kAxisForms, ", scale \"lin\" or \"log\"");
    if (!k.partner.empty()) meaning += cat("; or give ", k.partner);
    rows.push_back({cat(kSweep, ".", name), "(not swept)", std::string(k.unit), cat("values ", k.allowed()), meaning});
  }
  rows.push_back({"sweep.order", cat("(", join(sweep_axis_names(), ", "), ")"), "-", "every axis once",
                  "axis order, the first axis slowest in the flat cell index"});
  rows.push_back({"sweep.store", store_text(SweepOptions{}.store), "-", "quantity names",
                  cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", "),
                      " (status, regime, n, k, wall time and residual are always stored)")});
  for (const SweepInterval& row : sweep_intervals()) rows.push_back(key_row(row.info));
  return rows;
}

// The [optimise] rows of `vibromap keys`: one per free parameter, then the options.
std::vector<KeyRow> optimise_doc_rows() {
  std::vector<KeyRow> rows;
  for (const std::string_view name : sweep_axis_names()) {
    const SceneKey& k = axis_key(name);
    std::string meaning = cat("free parameter [", k.section, "] ", name, " and its box: ", kVariableForm,
                              ", scale \"lin\" or \"log\"");
    if (!k.partner.empty()) meaning += cat("; or free ", k.partner);
    rows.push_back({cat(kOptimise, ".", name), "(fixed)", std::string(k.unit), cat("bounds ", k.allowed()), meaning});
  }
  for (const OptimiseRow& row : optimise_rows()) {
    KeyRow r = key_row(row.info);
    r.allowed = row.allowed();
    rows.push_back(std::move(r));
  }
  return rows;
}

// A commented example [optimise] section: without the leading "# ", its lines parse.
void write_reference_optimise(std::ostream& os) {
  os << "\n# An optimisation for `vibromap optimise`: the values above are the base point and the free\n"
        "# parameters move inside their box (any of E1, E2, R1, R2, m2, k2|omega2, as NAME = { min, max[,\n"
        "# scale] }, scale \"lin\" (default) or \"log\"). The starts are the best cells of a map: `map`, or\n"
        "# the scene's [sweep] run first, or else the scene's point. [optimise] has no default: uncomment\n"
        "# and edit this example (jobs/paper/optimise_box.toml is a whole job).\n"
        "#\n"
        "# [optimise]\n"
        "# m2 = { min = 100.0, max = 310.0 }\n"
        "# E1 = { min = 2e4, max = 2.1e11, scale = \"log\" }\n";
  const auto line = [&](const std::string& lhs, std::string_view comment) {
    os << "# " << column(lhs, 44) << "  # " << comment << "\n";
  };
  for (const OptimiseRow& row : optimise_rows()) {
    const SceneKey& k = row.info;
    const std::string lhs = k.key == "map" ? std::string("map = \"box.h5\"") : cat(k.key, " = ", k.default_text);
    line(lhs, cat(k.meaning, unit_suffix(k.unit), ", ", row.allowed()));
  }
}

// A commented example [sweep] section: without the leading "# ", its lines parse.
void write_reference_sweep(std::ostream& os) {
  os << "\n# A grid for `vibromap sweep` over some of E1, E2, R1, R2, m2, k2|omega2; a scene without\n"
        "# [sweep] is one point, and the values above are the base of every cell. [sweep] has no\n"
        "# default: uncomment and edit this example. An axis is { from, to, n[, scale] } (n points,\n"
        "# ends exact, scale \"lin\" (default) or \"log\") or { values = [...][, scale] }; its values\n"
        "# must be allowed for the parameter's key above (E1 > 0, ...). Give k2 or omega2, not both.\n"
        "#\n"
        "# [sweep]\n"
        "# E1 = { from = 2e4, to = 2.1e11, n = 23, scale = \"log\" }\n"
        "# E2 = { values = [2e4, 1e6, 2.1e11] }\n";
  const auto line = [&](const std::string& lhs, std::string_view comment) {
    os << "# " << column(lhs, 44) << "  # " << comment << "\n";
  };
  line("order = [\"E1\", \"E2\"]", cat("axis order, first slowest; default ", join(sweep_axis_names(), ", ")));
  line(cat("store = ", store_text(SweepOptions{}.store)),
       cat("optional per-cell quantities, any of ", join(views(quantity_names()), ", ")));
  for (const SweepInterval& row : sweep_intervals()) {
    const SceneKey& k = row.info;
    line(cat(k.key, " = ", k.default_text), cat(k.meaning, unit_suffix(k.unit), ", ", k.allowed()));
  }
}

}  // namespace

void write_scene_keys(std::ostream& os) {
  std::vector<KeyRow> rows;
  for (const SceneKey& k : scene_keys()) rows.push_back(key_row(k));
  write_key_table(os, rows);
  os << "\n[sweep] (only in a sweep scene: a grid around the point above; example in jobs/reference.toml)\n";
  write_key_table(os, sweep_rows());
  os << "\n[optimise] (only in an optimisation scene: free parameters around the point above; example in "
        "jobs/reference.toml)\n";
  write_key_table(os, optimise_doc_rows());
}

void write_scene_key_summary(std::ostream& os) {
  for (std::string_view section : all_sections()) {
    std::string line = cat("  ", column(cat("[", section, "]"), 11));
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
        "# the rest state (x1, x2, v1, v2) = (0, D, 0, 0); set any subset of it.\n";
  for (std::string_view section : schema_sections()) {
    os << "\n[" << section << "]\n";
    for (const SceneKey& k : scene_keys()) {
      if (k.section == section) write_reference_key(os, k);
    }
  }
  write_reference_optimise(os);
  write_reference_sweep(os);
}

}  // namespace vibromap
