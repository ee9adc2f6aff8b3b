#include "map_fields.hpp"

#include <algorithm>
#include <limits>

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
  f.get_int = [](const CellResult& c) -> std::int64_t { return c.*M; };
  f.set_int = [](CellResult& c, std::int64_t v) { c.*M = static_cast<std::int8_t>(v); };
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
  f.get_int = [](const CellResult& c) -> std::int64_t { return c.*M; };
  f.set_int = [](CellResult& c, std::int64_t v) { c.*M = static_cast<std::int32_t>(v); };
  return f;
}

template <auto M>
MapField real_field(std::string name, std::string long_name, std::string units) {
  MapField f;
  f.name = std::move(name);
  f.fill = kNaN;
  f.long_name = std::move(long_name);
  f.units = std::move(units);
  f.get_real = [](const CellResult& c) { return c.*M; };
  f.set_real = [](CellResult& c, double v) { c.*M = v; };
  return f;
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
    f.get_int = [q](const CellResult& c) { return quantity_int(c, q); };
    f.set_int = [q](CellResult& c, std::int64_t v) { set_quantity_int(c, q, v); };
  } else {
    f.fill = kNaN;
    f.get_real = [q](const CellResult& c) { return c.value(q); };
    f.set_real = [q](CellResult& c, double v) { set_quantity(c, q, v); };
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

std::vector<MapField> map_fields(const std::vector<Quantity>& stored) {
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
  fields.push_back(count_field<&CellResult::n>("n", "period of the regime in forcing periods (0 where not periodic)"));
  fields.push_back(count_field<&CellResult::k>("k", "impacts per regime period (0 where not periodic)"));
  fields.push_back(real_field<&CellResult::wall_s>("wall_s", "wall-clock time spent on the cell", "s"));
  fields.push_back(
      real_field<&CellResult::steady_residual>("steady_residual", "relative residual of the steady-state test", "1"));
  for (const Quantity q : stored) fields.push_back(quantity_field(q));
  return fields;
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
