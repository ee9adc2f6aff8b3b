#include "map_fields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "vibromap/core/text.hpp"

namespace vibromap::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// CF flag_meanings: the enum's names from to_string, with '_' for '-' (CF meanings are
// blank-separated words), preceded by not_computed for code -1. Codes run -1..last.
template <class Enum>
std::string flag_meanings(Enum last, std::int8_t (*code)(Enum)) {
  std::string meanings = "not_computed";
  for (int i = 0; i <= code(last); ++i) {
    std::string name = to_string(static_cast<Enum>(i));
    std::replace(name.begin(), name.end(), '-', '_');
    meanings.append(" ").append(name);
  }
  return meanings;
}

std::vector<std::int8_t> flag_values(std::int8_t last) {
  std::vector<std::int8_t> values;
  for (int v = kNotComputed; v <= last; ++v) values.push_back(static_cast<std::int8_t>(v));
  return values;
}

// An int8 code field (fill -1, "not computed") stored in member M.
template <auto M>
MapField code_field(std::string name, std::string long_name, std::int8_t last, std::string meanings) {
  MapField f;
  f.name = std::move(name);
  f.file_type = ElementType::int8;
  f.integer = true;
  f.fill = -1.0;
  f.fill_attribute = false;
  f.long_name = std::move(long_name);
  f.flag_values = flag_values(last);
  f.flag_meanings = std::move(meanings);
  f.lo = kNotComputed;
  f.hi = last;
  f.get_int = [](const CellResult& c, std::size_t) -> std::int64_t { return c.*M; };
  f.set_int = [](CellResult& c, std::size_t, std::int64_t v) { c.*M = static_cast<std::int8_t>(v); };
  return f;
}

template <auto M>
MapField count_field(std::string name, std::string long_name) {
  MapField f;
  f.name = std::move(name);
  f.file_type = ElementType::int32;
  f.integer = true;
  f.fill = 0.0;
  f.fill_attribute = false;
  f.long_name = std::move(long_name);
  f.units = std::string(1, '1');  // (not = "1": GCC 12's false -Wrestrict, bug 105329)
  f.lo = 0;
  f.hi = std::numeric_limits<std::int32_t>::max();
  f.get_int = [](const CellResult& c, std::size_t) -> std::int64_t { return c.*M; };
  f.set_int = [](CellResult& c, std::size_t, std::int64_t v) { c.*M = static_cast<std::int32_t>(v); };
  return f;
}

template <auto M>
MapField real_field(std::string name, std::string long_name, std::string units) {
  MapField f;
  f.name = std::move(name);
  f.fill = kNaN;
  f.long_name = std::move(long_name);
  f.units = std::move(units);
  f.get_real = [](const CellResult& c, std::size_t) { return c.*M; };
  f.set_real = [](CellResult& c, std::size_t, double v) { c.*M = v; };
  return f;
}

// A field of the census's attractors, slot a = attractor a of the cell: made from a per-cell
// field of the same kind (its type, fill, flags, range), with get(const Attractor&) giving the
// file's value and set(Attractor&, value) taking it back: an integer field when get gives an
// integer (or bool), set then taking an int64; else a double.
template <class Get, class Set>
MapField attractor_field(MapField f, std::size_t slots, Get get, Set set) {
  f.slots = slots;
  const double fill = f.fill.value_or(0.0);
  if constexpr (std::is_integral_v<std::invoke_result_t<Get, const Attractor&>>) {
    f.get_int = [get, fill](const CellResult& c, std::size_t a) -> std::int64_t {
      return a < c.census.size() ? static_cast<std::int64_t>(get(c.census[a])) : static_cast<std::int64_t>(fill);
    };
    f.set_int = [set](CellResult& c, std::size_t a, std::int64_t v) {
      if (a < c.census.size()) set(c.census[a], v);
    };
  } else {
    f.get_real = [get, fill](const CellResult& c, std::size_t a) -> double {
      return a < c.census.size() ? get(c.census[a]) : fill;
    };
    f.set_real = [set](CellResult& c, std::size_t a, double v) {
      if (a < c.census.size()) set(c.census[a], v);
    };
  }
  return f;
}

// The code a listed attractor holds in a code dataset: -1 (not listed) is malformed there.
std::int64_t listed_code(std::int64_t v) {
  if (v < 0) throw std::invalid_argument("holds -1 (not listed) for a listed attractor");
  return v;
}

// An attractor field on member M: a double as it is, a bool as a 0/1 flag, an int as it is.
template <auto M>
MapField attractor_member(MapField f, std::size_t slots) {
  using Value = std::remove_cvref_t<decltype(std::declval<Attractor&>().*M)>;
  return attractor_field(
      std::move(f), slots, [](const Attractor& a) { return a.*M; },
      [](Attractor& a, auto v) {
        if constexpr (std::is_same_v<Value, bool>)
          a.*M = listed_code(v) != 0;
        else
          a.*M = static_cast<Value>(v);  // an int from an int64 in its dataset's range, or a double
      });
}

// Component I (x1, x2, v1, v2) of an attractor's first stroboscopic state: NaN when it has none.
template <int I>
MapField attractor_strobe(MapField f, std::size_t slots) {
  return attractor_field(
      std::move(f), slots, [](const Attractor& a) { return a.strobe.empty() ? kNaN : a.strobe.front()[I]; },
      [](Attractor& a, double v) {
        if (a.strobe.empty()) a.strobe.assign(1, Eigen::Vector4d::Constant(kNaN));
        a.strobe.front()[I] = v;
      });
}

// The attractors' first kMapStrobePoints period-start states: value a of a cell is attractor
// a / (S 4), state (a / 4) % S, component a % 4; NaN past the attractor's period (or none kept).
MapField attractor_strobe_states(MapField f, std::size_t slots) {
  constexpr std::size_t kPer = kMapStrobePoints * 4;
  f.slots = slots;
  f.inner = {kMapStrobePoints, 4};
  f.get_real = [](const CellResult& c, std::size_t a) -> double {
    const std::size_t i = a / kPer, p = (a / 4) % kMapStrobePoints;
    if (i >= c.census.size() || p >= c.census[i].strobe.size()) return kNaN;
    return c.census[i].strobe[p][static_cast<Eigen::Index>(a % 4)];
  };
  f.set_real = [](CellResult& c, std::size_t a, double v) {
    const std::size_t i = a / kPer, p = (a / 4) % kMapStrobePoints;
    if (i >= c.census.size() || std::isnan(v)) return;
    std::vector<Eigen::Vector4d>& strobe = c.census[i].strobe;
    if (strobe.size() <= p) strobe.resize(p + 1, Eigen::Vector4d::Constant(kNaN));
    strobe[p][static_cast<Eigen::Index>(a % 4)] = v;
  };
  return f;
}

// The census's datasets (map_file.hpp).
void add_census_fields(std::vector<MapField>& fields, std::size_t slots) {
  MapField count = count_field<&CellResult::n>("attractors", "attractors the census lists in the cell");
  count.lo = 0;
  count.hi = static_cast<std::int64_t>(slots);
  count.get_int = [](const CellResult& c, std::size_t) { return static_cast<std::int64_t>(c.census.size()); };
  count.set_int = [](CellResult& c, std::size_t, std::int64_t v) { c.census.resize(static_cast<std::size_t>(v)); };
  fields.push_back(count);
  fields.push_back(real_field<&CellResult::soft_fraction>(
      "soft_fraction", "basin fraction of the soft attractors (periodic with impacts, stable, Hertz-valid, k_con <= soft_kcon)", "1"));
  fields.push_back(real_field<&CellResult::unresolved_fraction>(
      "unresolved_fraction", "fraction of initial states still settling when the budget ran out", "1"));
  fields.push_back(real_field<&CellResult::unlisted_fraction>(
      "unlisted_fraction", "fraction of initial states reaching an attractor beyond census.max_attractors", "1"));
  fields.push_back(real_field<&CellResult::budget_fraction>(
      "budget_fraction",
      "fraction of initial states followed to analysis.max_periods without an early decision (as brute force)", "1"));
  fields.push_back(real_field<&CellResult::basin_entropy>(
      "basin_entropy",
      "basin entropy -sum f ln f over the shares of the listed attractors, the unresolved and the unlisted states", "1"));
  const auto code = [](std::string name, std::string long_name, std::int8_t last, std::string meanings) {
    return code_field<&CellResult::regime>(std::move(name), std::move(long_name), last, std::move(meanings));
  };
  using A = Attractor;
  fields.push_back(attractor_field(
      code("attractor_regime", "the attractor's regime; periodic (n,k) with attractor_n and attractor_k",
           regime_code(RegimeKind::failed), flag_meanings(RegimeKind::failed, &regime_code)),
      slots, [](const A& a) { return regime_code(a.regime.kind); },
      [](A& a, std::int64_t v) { a.regime.kind = static_cast<RegimeKind>(listed_code(v)); }));
  MapField stable = code("attractor_stable", "stability of the attractor's orbit from its Floquet multipliers", 1,
                         "unknown unstable stable");
  fields.push_back(attractor_member<&A::stable>(stable, slots));
  const auto flag = [&](std::string name, std::string long_name) {
    MapField f = code(std::move(name), std::move(long_name), 1, "not_listed no yes");
    return f;
  };
  fields.push_back(attractor_member<&A::hertz_valid>(
      flag("attractor_hertz_valid", "1 where the attractor's z_ratio is within the Hertz validity limit"), slots));
  fields.push_back(attractor_member<&A::from_rest>(flag("attractor_from_rest", "1 for the attractor rest reaches"), slots));
  fields.push_back(attractor_member<&A::soft>(
      flag("attractor_soft", "1 where the attractor is soft (periodic with impacts, stable, Hertz-valid, k_con <= soft_kcon)"), slots));
  fields.push_back(attractor_member<&A::transient>(
      flag("attractor_transient",
           "1 where states were seen to leave the non-periodic attractor (transient chaos: its fraction falls as "
           "analysis.max_periods grows)"),
      slots));
  fields.push_back(attractor_field(
      count_field<&CellResult::n>("attractor_n", "period of the attractor in forcing periods (0 where not periodic)"),
      slots, [](const A& a) { return a.regime.n; }, [](A& a, std::int64_t v) { a.regime.n = static_cast<int>(v); }));
  fields.push_back(attractor_field(
      count_field<&CellResult::k>("attractor_k", "impacts per period of the attractor (0 where not periodic)"), slots,
      [](const A& a) { return a.regime.k; }, [](A& a, std::int64_t v) { a.regime.k = static_cast<int>(v); }));
  const auto real = [](std::string name, std::string long_name, std::string units) {
    return real_field<&CellResult::T_con>(std::move(name), std::move(long_name), std::move(units));
  };
  fields.push_back(attractor_member<&A::T_con>(real("attractor_T_con", "duration of the attractor's longest impact", "s"), slots));
  fields.push_back(attractor_member<&A::k_con>(real("attractor_k_con", "softness T / T_con of the attractor's longest impact", "1"), slots));
  fields.push_back(attractor_member<&A::F_max>(real("attractor_F_max", "largest peak contact force of the attractor", "N"), slots));
  fields.push_back(attractor_member<&A::z_ratio>(real("attractor_z_ratio", "largest peak penetration over R* of the attractor", "1"), slots));
  fields.push_back(attractor_member<&A::max_floquet>(
      real("attractor_max_floquet", "largest |Floquet multiplier| of the attractor's orbit", "1"), slots));
  fields.push_back(attractor_member<&A::fraction>(
      real("attractor_fraction", "basin fraction: initial states reaching the attractor over all", "1"), slots));
  fields.push_back(attractor_member<&A::fraction_stderr>(
      real("attractor_fraction_stderr", "standard error sqrt(p (1 - p) / K) of the basin fraction", "1"), slots));
  fields.push_back(attractor_strobe<0>(real("attractor_x1", "x1 of the attractor's first stroboscopic state", "m"), slots));
  fields.push_back(attractor_strobe<1>(real("attractor_x2", "x2 of the attractor's first stroboscopic state", "m"), slots));
  fields.push_back(attractor_strobe<2>(real("attractor_v1", "v1 of the attractor's first stroboscopic state", "m/s"), slots));
  fields.push_back(attractor_strobe<3>(real("attractor_v2", "v2 of the attractor's first stroboscopic state", "m/s"), slots));
  fields.push_back(attractor_strobe_states(
      real("attractor_strobe",
           "the attractor's period-start states (x1, x2, v1, v2) in m and m/s, its first ones; NaN past its period", ""),
      slots));
}

// An int32 field of the census's attractors with its own fill and range (the shock's indices).
MapField index_field(std::string name, std::string long_name, std::int64_t lo, std::int64_t hi) {
  MapField f;
  f.name = std::move(name);
  f.file_type = ElementType::int32;
  f.integer = true;
  f.fill = -1.0;
  f.fill_attribute = false;
  f.long_name = std::move(long_name);
  f.units = std::string(1, '1');
  f.lo = lo;
  f.hi = hi;
  return f;
}

// The minimal critical shock's datasets (map_file.hpp), with census.shock.
void add_shock_fields(std::vector<MapField>& fields, std::size_t slots) {
  using A = Attractor;
  const auto real = [](std::string name, std::string long_name, std::string units) {
    return real_field<&CellResult::T_con>(std::move(name), std::move(long_name), std::move(units));
  };
  fields.push_back(attractor_field(
      code_field<&CellResult::regime>("attractor_shock_status", "outcome of the attractor's minimal critical shock search",
                                      static_cast<std::int8_t>(ShockStatus::failed),
                                      "not_listed not_computed found none not_periodic failed"),
      slots, [](const A& a) { return static_cast<int>(a.shock.status); },
      [](A& a, std::int64_t v) { a.shock.status = static_cast<ShockStatus>(listed_code(v)); }));
  fields.push_back(attractor_field(
      real("attractor_shock",
           "minimal critical shock: the least perturbation of a period-start state, in motion scales (L, omega L), "
           "that leads to another attractor (NaN where none was found)",
           "1"),
      slots, [](const A& a) { return a.shock.size; }, [](A& a, double v) { a.shock.size = v; }));
  fields.push_back(attractor_field(
      index_field("attractor_shock_to",
                  "index of the attractor the shock leads to (-2: one the cell does not list; -1: none)", -2,
                  static_cast<std::int64_t>(slots) - 1),
      slots, [](const A& a) { return a.shock.to; }, [](A& a, std::int64_t v) { a.shock.to = static_cast<int>(v); }));
  fields.push_back(attractor_field(
      code_field<&CellResult::regime>("attractor_shock_to_regime", "regime of the attractor the shock leads to",
                                      regime_code(RegimeKind::failed), flag_meanings(RegimeKind::failed, &regime_code)),
      slots, [](const A& a) { return regime_code(a.shock.to_regime.kind); },
      [](A& a, std::int64_t v) { a.shock.to_regime.kind = static_cast<RegimeKind>(listed_code(v)); }));
  fields.push_back(attractor_field(
      index_field("attractor_shock_strobe", "which stroboscopic state of the attractor the shock perturbs (-1: none)",
                  -1, std::numeric_limits<std::int32_t>::max()),
      slots, [](const A& a) { return a.shock.strobe_index; },
      [](A& a, std::int64_t v) { a.shock.strobe_index = static_cast<int>(v); }));
  const char* names[4] = {"attractor_shock_dx1", "attractor_shock_dx2", "attractor_shock_dv1", "attractor_shock_dv2"};
  const char* what[4] = {"x1", "x2", "v1", "v2"};
  for (int i = 0; i < 4; ++i)
    fields.push_back(attractor_field(
        real(names[i], cat("component ", what[i], " of the minimal critical shock's perturbation (NaN where none)"),
             i < 2 ? "m" : "m/s"),
        slots, [i](const A& a) { return a.shock.dx[i]; }, [i](A& a, double v) { a.shock.dx[i] = v; }));
}

MapField quantity_field(Quantity q) {
  MapField f;
  f.name = to_string(q);
  f.long_name = std::string(quantity_description(q));
  f.units = std::string(quantity_units(q));
  if (quantity_is_integer(q)) {
    f.file_type = ElementType::int64;
    f.integer = true;
    f.fill = 0.0;
    f.fill_attribute = false;
    f.lo = 0;
    f.hi = quantity_max(q);
    f.get_int = [q](const CellResult& c, std::size_t) { return quantity_int(c, q); };
    f.set_int = [q](CellResult& c, std::size_t, std::int64_t v) { set_quantity_int(c, q, v); };
  } else {
    f.fill = kNaN;
    f.get_real = [q](const CellResult& c, std::size_t) { return c.value(q); };
    f.set_real = [q](CellResult& c, std::size_t, double v) { set_quantity(c, q, v); };
  }
  return f;
}

}  // namespace

MapField done_field() {
  MapField f;
  f.name = "done";
  f.file_type = ElementType::uint8;
  f.integer = true;
  f.fill = 0.0;
  f.fill_attribute = false;
  f.long_name = "1 where the cell has been computed";
  f.lo = 0;
  f.hi = 1;
  return f;
}

std::vector<MapField> map_fields(const MapLayout& layout) {
  return map_fields(layout.stored, layout.attractors, layout.refine_levels, layout.census_shock, layout.fragility > 0.0);
}

std::vector<MapField> map_fields(const std::vector<Quantity>& stored, std::size_t attractors, int refine_levels,
                                 bool shock, bool fragility) {
  std::vector<MapField> fields;
  fields.push_back(code_field<&CellResult::status>("status", "outcome of the point solver",
                                                   status_code(SolveStatus::invalid_input),
                                                   flag_meanings(SolveStatus::invalid_input, &status_code)));
  fields.push_back(code_field<&CellResult::regime>("regime", "motion regime; periodic (n,k) with n and k",
                                                   regime_code(RegimeKind::failed),
                                                   flag_meanings(RegimeKind::failed, &regime_code)));
  fields.push_back(code_field<&CellResult::stable>(
      "stable", "stability of the periodic orbit from its Floquet multipliers (unknown where not computed)", 1,
      "not_computed unstable stable"));
  fields.back().flag_meanings = "unknown unstable stable";
  fields.push_back(code_field<&CellResult::soft>(
      "soft",
      "1 where the motion is soft: periodic with impacts, stable, Hertz-valid (z_ratio <= hertz_limit) and "
      "k_con <= soft_kcon",
      1, "not_computed no yes"));
  fields.push_back(count_field<&CellResult::n>("n", "period of the regime in forcing periods (0 where not periodic)"));
  fields.push_back(count_field<&CellResult::k>("k", "impacts per regime period (0 where not periodic)"));
  fields.push_back(real_field<&CellResult::wall_s>("wall_s", "wall-clock time spent on the cell", "s"));
  fields.push_back(
      real_field<&CellResult::steady_residual>("steady_residual", "relative residual of the steady-state test", "1"));
  for (const Quantity q : stored) fields.push_back(quantity_field(q));
  if (attractors > 0) add_census_fields(fields, attractors);
  if (attractors > 0 && shock) add_shock_fields(fields, attractors);
  if (refine_levels > 0) {
    fields.push_back(code_field<&CellResult::computed>(
        "computed", "how the point got its values: solved, inherited from the nearest solved corner of its block, or "
        "audited (inherited, then solved to check the inference; it holds its own solution)",
        2, "not_decided inherited solved audited"));
    fields.back().flag_values = {-1, 0, 1, 2};
    fields.push_back(code_field<&CellResult::level>(
        "level", "refinement level at which the point was decided (0: the coarse grid)",
        static_cast<std::int8_t>(refine_levels), ""));
    fields.back().flag_values.clear();
  }
  if (fragility)
    fields.push_back(code_field<&CellResult::fragile>(
        "fragile",
        "1 where a perturbation of the initial state (analysis.fragility, motion scales) ends on another attractor "
        "than the initial state: the cell's answer is not robust",
        1, "not_assessed no yes"));
  return fields;
}

std::vector<MapField> family_fields(std::size_t attractors) {
  if (attractors == 0) return {};
  MapField family;
  family.name = "family";
  family.file_type = ElementType::int32;
  family.integer = true;
  family.fill = -1.0;
  family.fill_attribute = false;
  family.long_name = "family of the attractor across the map (ids dense from 0, by first cell); -1 where not listed or "
                     "not matched yet";
  family.units = std::string(1, '1');
  family.slots = attractors;
  MapField flags = family;
  flags.name = "family_flags";
  flags.file_type = ElementType::int8;
  flags.long_name = "bits: 1 the attractor's regime differs from that of a matched neighbour (a label change within "
                    "its family), 2 a computed neighbour along some axis has no attractor matched to it (the "
                    "family's edge); -1 where not listed or not matched yet";
  return {family, flags};
}

std::uint64_t element_bytes(ElementType t) {
  switch (t) {
    case ElementType::int8:
    case ElementType::uint8: return 1;
    case ElementType::int32: return 4;
    case ElementType::int64:
    case ElementType::float64: break;
  }
  return 8;
}

Shape map_chunk_shape(const Shape& shape) {
  Shape chunk(shape.size(), 1);
  std::uint64_t inner = 1;
  for (std::size_t d = shape.size(); d-- > 0;) {
    const std::uint64_t n = std::max<std::uint64_t>(shape[d], 1);
    if (inner * n <= kMapChunkCells) {
      chunk[d] = static_cast<std::size_t>(n);
      inner *= n;
      continue;
    }
    chunk[d] = static_cast<std::size_t>(std::max<std::uint64_t>(1, kMapChunkCells / inner));
    break;
  }
  return chunk;
}

std::vector<CellSpan> chunk_spans(const Shape& shape, const Shape& chunk) {
  const std::size_t rank = shape.size();
  std::vector<std::uint64_t> stride(rank, 1);  // flat index step per axis
  for (std::size_t d = rank; d-- > 1;) stride[d - 1] = stride[d] * shape[d];
  std::vector<std::size_t> at(rank, 0);       // the chunk's first element, per axis
  std::vector<CellSpan> spans;
  if (rank == 0) return spans;
  for (std::size_t d = 0; d < rank; ++d)
    if (shape[d] == 0) return spans;
  for (;;) {
    std::uint64_t first = 0, last = 0;
    for (std::size_t d = 0; d < rank; ++d) {
      first += at[d] * stride[d];
      last += (std::min(at[d] + chunk[d], shape[d]) - 1) * stride[d];
    }
    spans.push_back({first, last + 1});
    std::size_t d = rank;
    while (d-- > 0) {
      at[d] += chunk[d];
      if (at[d] < shape[d]) break;
      at[d] = 0;
      if (d == 0) return spans;
    }
  }
}

}  // namespace vibromap::detail
