#include "vibromap/io/basins_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <span>

#include "vibromap/core/quantities.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "attribute_seal.hpp"
#include "index_scale.hpp"
#include "regime_flags.hpp"

// The layout is documented in basins_file.hpp.

namespace vibromap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fixed_text(const BasinsPlane& p) {
  std::string out;
  for (int i = 0; i < 4; ++i) {
    if (i == p.vars[0] || i == p.vars[1]) continue;
    char value[64];
    const auto end = std::to_chars(value, value + sizeof value, p.fixed[i]).ptr;  // shortest round trip
    if (!out.empty()) out += ' ';
    out.append(kStateNames[static_cast<std::size_t>(i)]).append("=").append(value, end);
  }
  return out;
}

void write_root(Hdf5File& f, const BasinsContent& c) {
  const BasinsPlane& p = c.plane;
  f.set_attribute("title", "vibromap basins: the attractor of each initial state of a plane");
  f.set_attribute("Conventions", "CF-1.8");
  f.set_attribute("vibromap_version", VIBROMAP_VERSION);
  f.set_attribute("scene", c.scene_text);
  f.set_attribute("identity", c.identity);
  f.set_attribute("plane", p.name());
  f.set_attribute("grid", std::to_string(p.axes[0].size()) + "x" + std::to_string(p.axes[1].size()));
  f.set_attribute("fixed", fixed_text(p));
  const std::array<double, 4> fixed{p.fixed[0], p.fixed[1], p.fixed[2], p.fixed[3]};
  f.set_attribute("fixed_state", std::span<const double>(fixed));
  f.set_attribute("complete", c.complete ? 1 : 0);
  f.set_attribute("pixels", static_cast<std::int64_t>(p.pixels()));
  f.set_attribute("pixels_done", static_cast<std::int64_t>(std::count(c.done.begin(), c.done.end(), 1)));
  f.set_attribute("pixels_overlap", static_cast<std::int64_t>(std::count(c.labels.begin(), c.labels.end(), kOverlapLabel)));
  f.set_attribute("attractors", static_cast<std::int64_t>(c.attractors.size()));
  f.set_attribute("soft_kcon", c.soft_kcon);
}

// The basin entropy of the labels and the uncertainty exponent's fit, as root attributes.
void write_entropy(Hdf5File& f, const BasinEntropySummary& e) {
  f.set_attribute("entropy_box", static_cast<std::int64_t>(e.box));
  f.set_attribute("entropy_boxes", static_cast<std::int64_t>(e.boxes));
  f.set_attribute("entropy_boundary_boxes", static_cast<std::int64_t>(e.boundary_boxes));
  f.set_attribute("basin_entropy", e.S_b);
  f.set_attribute("boundary_basin_entropy", e.S_bb);
  f.set_attribute("log2_test", to_string(e.verdict));
  if (!e.uncertain.empty())  // HDF5 stores no empty array: none when min(N0, N1) < 4 or nothing is done
    f.set_attribute("uncertainty_fraction", std::span<const double>(e.uncertain));
  f.set_attribute("uncertainty_exponent", e.alpha);
  f.set_attribute("boundary_dimension", e.dimension);
  f.set_attribute("uncertainty_fit_rms", e.fit_rms);
  f.set_attribute("uncertainty_fit_eps_lo", static_cast<std::int64_t>(e.eps_lo));
  f.set_attribute("uncertainty_fit_eps_hi", static_cast<std::int64_t>(e.eps_hi));
  f.set_attribute("uncertainty_fit_scales", static_cast<std::int64_t>(e.fit_scales));
  f.set_attribute("uncertainty_note", e.ok ? e.alpha_note : e.message);
}

void write_plane(Hdf5File& f, const BasinsContent& c) {
  const BasinsPlane& p = c.plane;
  std::array<Dataset, 2> scales;
  for (std::size_t d = 0; d < 2; ++d) {
    const int var = p.vars[d];
    const std::string name(kStateNames[static_cast<std::size_t>(var)]);
    scales[d] = f.write_dataset(name, p.axes[d]);
    scales[d].make_dimension_scale(name);
    scales[d].set_attribute("units", state_units(var));
    scales[d].set_attribute("long_name", "initial " + name + (var < 2 ? " (position of body " : " (velocity of body ") +
                                             std::to_string(var % 2 + 1) + ")");
  }
  const Shape shape{p.axes[1].size(), p.axes[0].size()};
  DatasetOptions o;
  o.fill_attribute = false;
  Dataset label = f.write_dataset("label", std::span<const int>(c.labels), shape, o);
  label.attach_dimension_scale(scales[1], 0);
  label.attach_dimension_scale(scales[0], 1);
  label.set_attribute("long_name", "index of the attractor the initial state settles into");
  const std::array<std::int8_t, 5> flags{-4, -3, -2, -1, 0};
  label.set_attribute("flag_values", std::span<const std::int8_t>(flags));
  label.set_attribute("flag_meanings", "not_computed overlap unlisted unresolved first_attractor");
  Dataset done = f.write_dataset("done", std::span<const std::uint8_t>(c.done), shape, o);
  done.attach_dimension_scale(scales[1], 0);
  done.attach_dimension_scale(scales[0], 1);
  done.set_attribute("long_name", "1 where the label is final");
}

// Per-attractor real fields: name, member, units.
struct RealField {
  const char* name;
  double Attractor::*member;
  const char* units;
};
constexpr RealField kReals[] = {{"T_con", &Attractor::T_con, "s"},     {"k_con", &Attractor::k_con, "1"},
                                {"F_max", &Attractor::F_max, "N"},     {"z_ratio", &Attractor::z_ratio, "1"},
                                {"z_max", &Attractor::z_max, "m"},     {"v_in", &Attractor::v_in, "m/s"},
                                {"impulse", &Attractor::impulse, "N s"}, {"max_floquet", &Attractor::max_floquet, "1"},
                                {"fraction", &Attractor::fraction, "1"}};

void write_attractors(Hdf5File& f, const BasinsContent& c) {
  const std::size_t A = c.attractors.size();
  if (A == 0) return;  // HDF5 stores no empty simple dataspace; the reader takes "none"
  std::vector<int> index(A), n(A), k(A), points(A);
  std::vector<std::int8_t> regime(A), stable(A);
  std::vector<std::uint8_t> periodic(A), hertz(A), soft(A);
  std::vector<std::int64_t> pixels(A);
  std::size_t S = 1;
  for (const Attractor& a : c.attractors) S = std::max(S, a.strobe.size());
  std::vector<double> strobe(A * S * 4, kNaN);
  for (std::size_t i = 0; i < A; ++i) {
    const Attractor& a = c.attractors[i];
    index[i] = static_cast<int>(i);
    regime[i] = regime_code(a.regime.kind);
    n[i] = a.regime.n;
    k[i] = a.regime.k;
    periodic[i] = a.periodic ? 1 : 0;
    hertz[i] = a.hertz_valid ? 1 : 0;
    soft[i] = a.soft ? 1 : 0;
    stable[i] = static_cast<std::int8_t>(a.stable);
    pixels[i] = a.count;
    points[i] = static_cast<int>(a.strobe.size());
    for (std::size_t s = 0; s < a.strobe.size(); ++s)
      for (int v = 0; v < 4; ++v) strobe[(i * S + s) * 4 + static_cast<std::size_t>(v)] = a.strobe[s][v];
  }
  Dataset coordinate = f.write_dataset("attractor", std::span<const int>(index));
  coordinate.make_dimension_scale("attractor");
  coordinate.set_attribute("long_name", "index of the attractor, by pixel count");
  const auto attach = [&](Dataset d, const char* long_name) {
    d.attach_dimension_scale(coordinate, 0);
    d.set_attribute("long_name", long_name);
    return d;
  };
  Dataset rd = attach(f.write_dataset("regime", std::span<const std::int8_t>(regime)), "regime code");
  detail::set_regime_flags(rd);
  attach(f.write_dataset("n", std::span<const int>(n)), "period in forcing periods");
  attach(f.write_dataset("k", std::span<const int>(k)), "impacts per period nT");
  attach(f.write_dataset("periodic", std::span<const std::uint8_t>(periodic)), "1 periodic, 0 non-periodic");
  attach(f.write_dataset("hertz_valid", std::span<const std::uint8_t>(hertz)), "1 when Hertz theory holds");
  attach(f.write_dataset("soft", std::span<const std::uint8_t>(soft)), "stable, Hertz-valid and k_con <= soft_kcon");
  attach(f.write_dataset("stable", std::span<const std::int8_t>(stable)), "1 stable, 0 unstable, -1 unknown");
  for (const RealField& r : kReals) {
    std::vector<double> v(A);
    for (std::size_t i = 0; i < A; ++i) v[i] = c.attractors[i].*(r.member);
    Dataset d = attach(f.write_dataset(r.name, std::span<const double>(v)), r.name);
    d.set_attribute("units", r.units);
  }
  attach(f.write_dataset("pixels", std::span<const std::int64_t>(pixels)), "pixels in the basin");
  attach(f.write_dataset("first_pixel", std::span<const std::int64_t>(c.first_pixel)), "first pixel (flat) in the basin");
  attach(f.write_dataset("strobe_points", std::span<const int>(points)), "stroboscopic states of the orbit");
  const Dataset period_start = detail::write_index_scale(f, "period_start", S, "period start within the orbit");
  const Dataset state = detail::write_flag_scale(f, "state", {"x1", "x2", "v1", "v2"}, "state variable");
  Dataset sd = f.write_dataset("strobe", std::span<const double>(strobe), {A, S, 4});
  sd.attach_dimension_scale(coordinate, 0);
  sd.attach_dimension_scale(period_start, 1);
  sd.attach_dimension_scale(state, 2);
  sd.set_attribute("long_name", "stroboscopic states (x1, x2, v1, v2) at period starts, m and m/s");
}

template <class T>
std::vector<T> read_as(const Dataset& d) {
  std::vector<T> out(d.size());
  if (!out.empty()) d.read_flat<T>(0, std::span<T>(out));
  return out;
}

void read_attractors(const Hdf5File& f, BasinsContent& c) {
  const std::size_t A = static_cast<std::size_t>(f.read_int_attribute("attractors"));
  c.attractors.assign(A, Attractor{});
  if (A == 0) return;
  const auto regime = f.open_dataset("regime").read_int();
  const auto n = f.open_dataset("n").read_int(), k = f.open_dataset("k").read_int();
  const auto periodic = f.open_dataset("periodic").read_int(), hertz = f.open_dataset("hertz_valid").read_int();
  const auto soft = f.open_dataset("soft").read_int(), stable = f.open_dataset("stable").read_int();
  const auto pixels = f.open_dataset("pixels").read_int(), points = f.open_dataset("strobe_points").read_int();
  c.first_pixel = f.open_dataset("first_pixel").read_int();
  const Dataset sd = f.open_dataset("strobe");
  const std::vector<double> strobe = sd.read_double();
  const std::size_t S = sd.shape().at(1);
  if (regime.size() != A || c.first_pixel.size() != A || sd.shape().at(0) != A)
    throw IoError(f.path() + ": the attractor datasets disagree with the attribute 'attractors'");
  for (const RealField& r : kReals) {
    const auto v = f.open_dataset(r.name).read_double();
    for (std::size_t i = 0; i < A; ++i) c.attractors[i].*(r.member) = v.at(i);
  }
  for (std::size_t i = 0; i < A; ++i) {
    Attractor& a = c.attractors[i];
    a.regime = Regime{static_cast<RegimeKind>(regime[i]), static_cast<int>(n[i]), static_cast<int>(k[i])};
    a.periodic = periodic[i] != 0;
    a.hertz_valid = hertz[i] != 0;
    a.soft = soft[i] != 0;
    a.stable = static_cast<int>(stable[i]);
    a.count = static_cast<int>(pixels[i]);
    const std::size_t m = std::min(S, static_cast<std::size_t>(std::max<std::int64_t>(points[i], 0)));
    for (std::size_t s = 0; s < m; ++s) {
      const double* x = &strobe[(i * S + s) * 4];
      a.strobe.emplace_back(x[0], x[1], x[2], x[3]);
    }
  }
}

}  // namespace

void write_basins_file(const std::string& path, const BasinsContent& c) {
  write_hdf5_atomically(path, [&](Hdf5File& f) {
    write_root(f, c);
    write_entropy(f, c.entropy);
    write_plane(f, c);
    write_attractors(f, c);
    detail::seal_attributes(f, kBasinsFormat);  // last: the format version, then the seal over every attribute
  });
}

BasinsContent read_basins_file(const std::string& path) {
  const Hdf5File f(path, FileMode::read_only);
  detail::verify_file(f, kBasinsFormat);  // another version, or damage, before any value is read
  for (const char* name : {"plane", "identity", "fixed_state", "label", "done"})
    if (!f.has_attribute(name) && !f.exists(name)) throw IoError(path + ": not a basins file of vibromap (no '" + name + "')");
  BasinsContent c;
  c.scene_text = f.read_string_attribute("scene");
  c.identity = f.read_string_attribute("identity");
  c.soft_kcon = f.read_double_attribute("soft_kcon");
  c.complete = f.read_int_attribute("complete") != 0;
  const std::string plane = f.read_string_attribute("plane");
  const auto comma = plane.find(',');
  if (comma == std::string::npos) throw IoError(path + ": a bad attribute 'plane' ('" + plane + "')");
  const std::array<std::string, 2> names{plane.substr(0, comma), plane.substr(comma + 1)};
  for (std::size_t d = 0; d < 2; ++d) {
    c.plane.vars[d] = state_index(names[d]);
    if (c.plane.vars[d] < 0) throw IoError(path + ": a bad attribute 'plane' ('" + plane + "')");
    c.plane.axes[d] = f.open_dataset(names[d]).read_double();
  }
  const auto fixed = f.read_double_array_attribute("fixed_state");
  if (fixed.size() != 4) throw IoError(path + ": the attribute 'fixed_state' does not hold 4 values");
  c.plane.fixed = Eigen::Vector4d(fixed[0], fixed[1], fixed[2], fixed[3]);
  const Dataset label = f.open_dataset("label");
  if (label.size() != c.plane.pixels()) throw IoError(path + ": 'label' does not match the plane's grid");
  c.labels = read_as<std::int32_t>(label);
  c.done = read_as<std::uint8_t>(f.open_dataset("done"));
  if (c.done.size() != c.labels.size()) throw IoError(path + ": 'done' does not match 'label'");
  read_attractors(f, c);
  return c;
}

}  // namespace vibromap
