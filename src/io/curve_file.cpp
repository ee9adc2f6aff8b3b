#include "vibromap/io/curve_file.hpp"

#include <cmath>
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

void column(Group& g, const Dataset& scale, const std::string& name, const std::vector<double>& values,
            const std::string& units, const std::string& long_name) {
  Dataset d = g.write_dataset(name, std::span<const double>(values));
  d.attach_dimension_scale(scale, 0);
  if (!units.empty()) d.set_attribute("units", units);
  d.set_attribute("long_name", long_name);
}

// The orbit's values of one curve, NaN where it has no contact.
void write_cycles(Group& g, const Dataset& point, const std::vector<CurveCycle>& cycles) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto per_point = [&](const std::string& name, auto get, const std::string& units, const std::string& what) {
    std::vector<double> v;
    for (const CurveCycle& c : cycles) v.push_back(c.impacts > 0 ? get(c) : nan);
    column(g, point, name, v, units, what);
  };
  per_point("T_con", [](const CurveCycle& c) { return c.T_con; }, "s", "duration of the longest impact");
  per_point("k_con", [](const CurveCycle& c) { return c.k_con; }, "1", "T / T_con of the longest impact");
  per_point("z_ratio", [](const CurveCycle& c) { return c.z_ratio; }, "1",
            "largest peak penetration over the reduced radius R*");
  per_point("F_max", [](const CurveCycle& c) { return c.F_max; }, "N", "largest peak contact force");
}

void write_multipliers(Group& g, const Dataset& point, const Curve& c) {
  const std::size_t P = c.points.size();
  const Dataset multiplier = write_index_scale(g, "multiplier", 4, "Floquet multiplier, largest |mu| first");
  for (const bool imag : {false, true}) {
    std::vector<double> v(P * 4, 0.0);
    for (std::size_t i = 0; i < P; ++i)
      for (std::size_t k = 0; k < 4 && k < c.points[i].multipliers.size(); ++k)
        v[i * 4 + k] = imag ? c.points[i].multipliers[k].imag() : c.points[i].multipliers[k].real();
    Dataset m = g.write_dataset(imag ? "multipliers_im" : "multipliers_re", std::span<const double>(v), {P, 4});
    m.attach_dimension_scale(point, 0);
    m.attach_dimension_scale(multiplier, 1);
    m.set_attribute("long_name", imag ? "imaginary part of the Floquet multipliers" : "real part of the Floquet multipliers");
  }
}

void write_codim2(Group& g, const CurveFileData& data, const Curve& c) {
  Group h = g.create_group("codim2");
  const Dataset dim = write_index_scale(h, "codim2", c.codim2.size(), "codimension-two point, in the order found");
  std::vector<double> p, q;
  std::vector<std::string> kind;
  for (const Codim2Point& x : c.codim2) {
    p.push_back(x.param);
    q.push_back(x.param2);
    kind.push_back(x.kind);
  }
  column(h, dim, "param", p, data.axis.units, data.axis.long_name);
  column(h, dim, "param2", q, data.axis2.units, data.axis2.long_name);
  Dataset k = h.write_strings("kind", std::span<const std::string>(kind));
  k.attach_dimension_scale(dim, 0);
  k.set_attribute("long_name", "what meets there: <curve kind>+<other kind>, or cusp");
}

void write_curve(Hdf5File& file, const CurveFileData& data, std::size_t i) {
  const Curve& c = data.curves[i];
  Group g = file.create_group("curve_" + std::to_string(i));
  g.set_attribute("kind", c.spec.label);
  g.set_attribute("stop", c.stop);
  g.set_attribute("n", c.n);
  const Dataset point = write_index_scale(g, "point", c.points.size(), "curve point, ordered along the curve");
  std::vector<double> p, q, residual;
  std::vector<std::int8_t> stable;
  for (const CurvePoint& x : c.points) {
    p.push_back(x.param);
    q.push_back(x.param2);
    residual.push_back(x.residual);
    stable.push_back(x.stable ? 1 : 0);
  }
  column(g, point, "param", p, data.axis.units, data.axis.long_name);
  column(g, point, "param2", q, data.axis2.units, data.axis2.long_name);
  write_cycles(g, point, data.cycles.at(i));
  Dataset st = g.write_dataset("stable", std::span<const std::int8_t>(stable));
  st.attach_dimension_scale(point, 0);
  st.set_attribute("long_name", "1 where every Floquet multiplier has |mu| < 1");
  write_multipliers(g, point, c);
  column(g, point, "residual", residual, "1", "|defining condition| at the point (scaled)");
  write_codim2(g, data, c);
}

}  // namespace

void write_curves(const std::string& path, const CurveFileData& data) {
  write_hdf5_atomically(path, [&](Hdf5File& file) {
    for (std::size_t i = 0; i < data.curves.size(); ++i) write_curve(file, data, i);
    detail::set_provenance(file, "vibromap curves of codimension-one points in two parameters", data.scene_text,
                           data.axis.key);
    file.set_attribute("vibromap_file", "curves");
    file.set_attribute("param", data.axis.key);
    file.set_attribute("param2", data.axis2.key);
    file.set_attribute("param_unit", data.axis.units == "1" ? std::string() : data.axis.units);
    file.set_attribute("param2_unit", data.axis2.units == "1" ? std::string() : data.axis2.units);
    detail::seal_attributes(file, kCurveFormat);  // last: the format version, then the seal over every attribute (attribute_seal.hpp)
  });
}

}  // namespace vibromap
