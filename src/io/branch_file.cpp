#include "vibromap/io/branch_file.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "attribute_seal.hpp"
#include "index_scale.hpp"
#include "provenance.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {
namespace {

using detail::write_index_scale;

void column(Hdf5File& file, const Dataset& scale, const std::string& name, const std::vector<double>& values,
            const std::string& units, const std::string& long_name) {
  Dataset d = file.write_dataset(name, std::span<const double>(values));
  d.attach_dimension_scale(scale, 0);
  if (!units.empty()) d.set_attribute("units", units);
  d.set_attribute("long_name", long_name);
}

void int_column(Hdf5File& file, const std::string& name, const std::vector<int>& v, const Dataset& dim,
                const std::string& what) {
  Dataset d = file.write_dataset(name, std::span<const int>(v));
  d.attach_dimension_scale(dim, 0);
  d.set_attribute("long_name", what);
}

constexpr const char* kStateNames[] = {"x1", "x2", "v1", "v2"};
constexpr const char* kStateUnits[] = {"m", "m", "m/s", "m/s"};

// The points and bifurcations of every branch, flattened (branch by branch), with their owners.
struct FlatBranches {
  std::vector<const BranchPoint*> pts;
  std::vector<const BranchCycle*> cycles;
  std::vector<int> point_branch, bif_branch;
  std::vector<const Bifurcation*> bif;
  std::size_t strobes = 1;  // the longest period, the strobe dimension
};

FlatBranches flatten(const BranchData& data) {
  FlatBranches f;
  for (std::size_t k = 0; k < data.branches.size(); ++k) {
    const Branch& b = data.branches[k];
    for (std::size_t i = 0; i < b.points.size(); ++i) {
      f.pts.push_back(&b.points[i]);
      f.cycles.push_back(&data.cycles.at(k).at(i));
      f.point_branch.push_back(static_cast<int>(k));
    }
    for (const Bifurcation& x : b.bifurcations) {
      f.bif.push_back(&x);
      f.bif_branch.push_back(static_cast<int>(k));
    }
    f.strobes = std::max(f.strobes, static_cast<std::size_t>(b.n));
  }
  return f;
}

// The per-point columns over the "point" dimension, which it returns.
Dataset write_points(Hdf5File& file, const BranchData& data, const FlatBranches& f) {
  const std::size_t P = f.pts.size();
  Dataset point = write_index_scale(file, "point", P, "branch point, by branch, each in arclength order");
  const auto per_point = [&](const std::string& name, auto get, const std::string& units, const std::string& what) {
    std::vector<double> v;
    for (std::size_t i = 0; i < P; ++i) v.push_back(get(i));
    column(file, point, name, v, units, what);
  };
  per_point("param", [&](std::size_t i) { return f.pts[i]->param; }, data.axis.units, data.axis.long_name);
  for (int c = 0; c < 4; ++c)
    per_point(kStateNames[c], [&](std::size_t i) { return f.pts[i]->y[c]; }, kStateUnits[c],
              std::string(kStateNames[c]) + " of the orbit at a period start");
  per_point("x1_max", [&](std::size_t i) { return f.pts[i]->x1_max; }, "m", "largest x1 over the cycle");
  per_point("x2_max", [&](std::size_t i) { return f.pts[i]->x2_max; }, "m", "largest x2 over the cycle");
  per_point("clearance_min", [&](std::size_t i) { return f.pts[i]->clearance_min; }, "m",
            "least x2 - x1 over the cycle (negative: contact)");
  per_point("T_con", [&](std::size_t i) { return f.cycles[i]->T_con; }, "s", "duration of the longest impact");
  per_point("k_con", [&](std::size_t i) { return f.cycles[i]->k_con; }, "1", "T / T_con of the longest impact");
  per_point("F_max", [&](std::size_t i) { return f.cycles[i]->F_max; }, "N", "largest peak contact force");
  std::vector<int> impacts;
  std::vector<std::int8_t> stable;
  for (std::size_t i = 0; i < P; ++i) {
    impacts.push_back(f.cycles[i]->impacts);
    stable.push_back(f.pts[i]->stable ? 1 : 0);
  }
  int_column(file, "impacts", impacts, point, "impacts per cycle");
  int_column(file, "point_branch", f.point_branch, point, "the branch of the point (index into branch)");
  Dataset st = file.write_dataset("stable", std::span<const std::int8_t>(stable));
  st.attach_dimension_scale(point, 0);
  st.set_attribute("long_name", "1 where every Floquet multiplier has |mu| < 1");
  return point;
}

// Per point: x1 at each period start of the cycle, and the Floquet multipliers.
void write_cycles(Hdf5File& file, const FlatBranches& f, const Dataset& point) {
  const std::size_t P = f.pts.size(), S = f.strobes;
  const Dataset strobe = write_index_scale(file, "strobe", S, "period start within the cycle");
  std::vector<double> x1(P * S, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < P; ++i)
    for (std::size_t k = 0; k < f.pts[i]->strobe.size() && k < S; ++k) x1[i * S + k] = f.pts[i]->strobe[k][0];
  Dataset d = file.write_dataset("strobe_x1", std::span<const double>(x1), {P, S});
  d.attach_dimension_scale(point, 0);
  d.attach_dimension_scale(strobe, 1);
  d.set_attribute("units", "m");
  d.set_attribute("long_name", "x1 at the period starts of the cycle (NaN beyond the branch's period)");
  const Dataset multiplier = write_index_scale(file, "multiplier", 4, "Floquet multiplier, largest |mu| first");
  for (const bool imag : {false, true}) {
    std::vector<double> v(P * 4, 0.0);
    for (std::size_t i = 0; i < P; ++i)
      for (std::size_t k = 0; k < 4 && k < f.pts[i]->multipliers.size(); ++k)
        v[i * 4 + k] = imag ? f.pts[i]->multipliers[k].imag() : f.pts[i]->multipliers[k].real();
    Dataset m = file.write_dataset(imag ? "multiplier_im" : "multiplier_re", std::span<const double>(v), {P, 4});
    m.attach_dimension_scale(point, 0);
    m.attach_dimension_scale(multiplier, 1);
    m.set_attribute("long_name", imag ? "imaginary part of the Floquet multipliers" : "real part of the Floquet multipliers");
  }
}

// The per-branch columns; returns the branches' stop reasons, one line each.
std::string write_branches(Hdf5File& file, const BranchData& data) {
  const Dataset branch =
      write_index_scale(file, "branch", data.branches.size(), "branch: 0 followed from the start, then the switched ones");
  std::vector<int> bn, bp, bb;
  std::string stops;
  for (const Branch& b : data.branches) {
    bn.push_back(b.n);
    bp.push_back(b.parent);
    bb.push_back(b.born_at);
    stops += (stops.empty() ? "" : "\n") + b.stop;
  }
  int_column(file, "branch_n", bn, branch, "period of the branch's orbits, forcing periods");
  int_column(file, "branch_parent", bp, branch, "the branch it was switched from (-1: none)");
  int_column(file, "branch_born_at", bb, branch,
             "the parent's period doubling it was switched at, a bifurcation index within the parent (-1: none)");
  return stops;
}

void write_bifurcations(Hdf5File& file, const BranchData& data, const FlatBranches& f) {
  const std::size_t B = f.bif.size();
  const Dataset bifurcation = write_index_scale(file, "bifurcation", B, "located bifurcation, by branch, in the order found");
  std::vector<std::int8_t> type;
  for (const Bifurcation* b : f.bif) type.push_back(static_cast<std::int8_t>(b->type));
  Dataset ty = file.write_dataset("bifurcation_type", std::span<const std::int8_t>(type));
  ty.attach_dimension_scale(bifurcation, 0);
  const std::vector<std::int8_t> flags{0, 1, 2, 3};
  ty.set_attribute("flag_values", std::span<const std::int8_t>(flags));
  ty.set_attribute("flag_meanings", "fold period_doubling neimark_sacker grazing");
  int_column(file, "bifurcation_branch", f.bif_branch, bifurcation, "the branch it was located on");
  const auto per_bif = [&](const std::string& name, auto get, const std::string& u, const std::string& what) {
    std::vector<double> v;
    for (std::size_t i = 0; i < B; ++i) v.push_back(get(f.bif[i]->at));
    column(file, bifurcation, name, v, u, what);
  };
  per_bif("bifurcation_param", [](const BranchPoint& q) { return q.param; }, data.axis.units, "the key at the bifurcation");
  for (int c = 0; c < 4; ++c)
    per_bif(std::string("bifurcation_") + kStateNames[c], [c](const BranchPoint& q) { return q.y[c]; }, kStateUnits[c],
            std::string(kStateNames[c]) + " of the orbit at the bifurcation");
}

}  // namespace

void write_branch(const std::string& path, const BranchData& data) {
  const FlatBranches flat = flatten(data);
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    const Dataset point = write_points(file, data, flat);
    write_cycles(file, flat, point);
    const std::string stops = write_branches(file, data);
    write_bifurcations(file, data, flat);
    detail::set_provenance(file, "vibromap periodic-orbit branch", data.scene_text, data.axis.key);
    file.set_attribute("units", data.axis.units);
    file.set_attribute("n", data.branches.empty() ? 1 : data.branches.front().n);
    file.set_attribute("stop", data.branches.empty() ? std::string() : data.branches.front().stop);
    file.set_attribute("stops", stops);
    detail::seal_attributes(file, kBranchFormat);  // last: the format version, then the seal over every attribute (attribute_seal.hpp)
  });
}

}  // namespace vibromap
