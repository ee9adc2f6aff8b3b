#include "vibromap/io/branch_file.hpp"

#include <cstdint>
#include <span>

#include "provenance.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {
namespace {

Dataset coordinate(Hdf5File& file, const std::string& name, std::size_t n, const std::string& long_name) {
  std::vector<int> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<int>(i);
  Dataset d = file.write_dataset(name, std::span<const int>(index));
  d.make_dimension_scale(name);
  d.set_attribute("long_name", long_name);
  return d;
}

void column(Hdf5File& file, const Dataset& scale, const std::string& name, const std::vector<double>& values,
            const std::string& units, const std::string& long_name) {
  Dataset d = file.write_dataset(name, std::span<const double>(values));
  d.attach_dimension_scale(scale, 0);
  if (!units.empty()) d.set_attribute("units", units);
  d.set_attribute("long_name", long_name);
}

}  // namespace

void write_branch(const std::string& path, const BranchData& data) {
  const auto& pts = data.branch.points;
  const auto& bif = data.branch.bifurcations;
  const std::size_t P = pts.size(), B = bif.size();
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    const Dataset point = coordinate(file, "point", P, "branch point, in arclength order");
    const auto per_point = [&](const std::string& name, auto get, const std::string& units, const std::string& what) {
      std::vector<double> v;
      for (std::size_t i = 0; i < P; ++i) v.push_back(get(i));
      column(file, point, name, v, units, what);
    };
    per_point("param", [&](std::size_t i) { return pts[i].param; }, data.axis.units, data.axis.long_name);
    const char* names[] = {"x1", "x2", "v1", "v2"};
    const char* units[] = {"m", "m", "m/s", "m/s"};
    for (int c = 0; c < 4; ++c)
      per_point(names[c], [&](std::size_t i) { return pts[i].y[c]; }, units[c],
                std::string(names[c]) + " of the orbit at a period start");
    per_point("x1_max", [&](std::size_t i) { return pts[i].x1_max; }, "m", "largest x1 over the cycle");
    per_point("x2_max", [&](std::size_t i) { return pts[i].x2_max; }, "m", "largest x2 over the cycle");
    per_point("clearance_min", [&](std::size_t i) { return pts[i].clearance_min; }, "m",
              "least x2 - x1 over the cycle (negative: contact)");
    per_point("T_con", [&](std::size_t i) { return data.cycles[i].T_con; }, "s", "duration of the longest impact");
    per_point("k_con", [&](std::size_t i) { return data.cycles[i].k_con; }, "1", "T / T_con of the longest impact");
    per_point("F_max", [&](std::size_t i) { return data.cycles[i].F_max; }, "N", "largest peak contact force");
    std::vector<int> impacts;
    std::vector<std::int8_t> stable;
    for (std::size_t i = 0; i < P; ++i) {
      impacts.push_back(data.cycles[i].impacts);
      stable.push_back(pts[i].stable ? 1 : 0);
    }
    Dataset im = file.write_dataset("impacts", std::span<const int>(impacts));
    Dataset st = file.write_dataset("stable", std::span<const std::int8_t>(stable));
    im.attach_dimension_scale(point, 0);
    st.attach_dimension_scale(point, 0);
    im.set_attribute("long_name", "impacts per cycle");
    st.set_attribute("long_name", "1 where every Floquet multiplier has |mu| < 1");
    const Dataset multiplier = coordinate(file, "multiplier", 4, "Floquet multiplier, largest |mu| first");
    for (const bool imag : {false, true}) {
      std::vector<double> v(P * 4, 0.0);
      for (std::size_t i = 0; i < P; ++i)
        for (std::size_t k = 0; k < 4 && k < pts[i].multipliers.size(); ++k)
          v[i * 4 + k] = imag ? pts[i].multipliers[k].imag() : pts[i].multipliers[k].real();
      Dataset d = file.write_dataset(imag ? "multiplier_im" : "multiplier_re", std::span<const double>(v), {P, 4});
      d.attach_dimension_scale(point, 0);
      d.attach_dimension_scale(multiplier, 1);
      d.set_attribute("long_name", imag ? "imaginary part of the Floquet multipliers" : "real part of the Floquet multipliers");
    }
    const Dataset bifurcation = coordinate(file, "bifurcation", B, "located bifurcation, in the order found");
    std::vector<std::int8_t> type;
    for (const Bifurcation& b : bif) type.push_back(static_cast<std::int8_t>(b.type));
    Dataset ty = file.write_dataset("bifurcation_type", std::span<const std::int8_t>(type));
    ty.attach_dimension_scale(bifurcation, 0);
    const std::vector<std::int8_t> flags{0, 1, 2, 3};
    ty.set_attribute("flag_values", std::span<const std::int8_t>(flags));
    ty.set_attribute("flag_meanings", "fold period_doubling neimark_sacker grazing");
    const auto per_bif = [&](const std::string& name, auto get, const std::string& u, const std::string& what) {
      std::vector<double> v;
      for (std::size_t i = 0; i < B; ++i) v.push_back(get(bif[i].at));
      column(file, bifurcation, name, v, u, what);
    };
    per_bif("bifurcation_param", [](const BranchPoint& q) { return q.param; }, data.axis.units, "the key at the bifurcation");
    for (int c = 0; c < 4; ++c)
      per_bif(std::string("bifurcation_") + names[c], [c](const BranchPoint& q) { return q.y[c]; }, units[c],
              std::string(names[c]) + " of the orbit at the bifurcation");
    detail::set_provenance(file, "vibromap periodic-orbit branch", data.scene_text, data.axis.key);
    file.set_attribute("units", data.axis.units);
    file.set_attribute("n", data.n);
    file.set_attribute("stop", data.branch.stop);
  });
}

}  // namespace vibromap
