#pragma once
// Internal to the map file: the datasets a map holds per cell (map_file.hpp documents the
// layout), each with its type, fill value, attributes and the CellResult member it stores;
// and the chunk geometry shared by all of them.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vibromap/core/quantities.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap::detail {

struct MapField {
  std::string name;
  ElementType file_type = ElementType::float64;
  bool integer = false;                    // read and written as int64 (else as double)
  std::optional<double> fill;              // value of a cell not done
  bool fill_attribute = true;              // _FillValue attribute (floats only: xarray masks it)
  std::string long_name, units;
  std::vector<std::int8_t> flag_values;    // CF flags of the code datasets
  std::string flag_meanings;
  std::int64_t lo = 0, hi = 0;             // integer fields: the valid range of a done cell
  // Per cell (slots == 0): the accessors below take slot 0. Per (cell, attractor) of a census
  // (slots == the map's attractor dimension): one more dimension; slot a of a cell listing
  // fewer attractors holds the fill value, and setting it does nothing.
  std::size_t slots = 0;
  // Dimensions after the attractor's (attractor_strobe: period start and state); values are
  // slot-major, then these dimensions row-major, so slot a's values are the a-th run of them.
  std::vector<std::size_t> inner;
  std::function<double(const CellResult&, std::size_t)> get_real;
  std::function<void(CellResult&, std::size_t, double)> set_real;
  std::function<std::int64_t(const CellResult&, std::size_t)> get_int;
  std::function<void(CellResult&, std::size_t, std::int64_t)> set_int;

  std::size_t width() const {  // values per cell
    std::size_t w = slots == 0 ? 1 : slots;
    for (const std::size_t n : inner) w *= n;
    return w;
  }
};

// /done (not a CellResult member: written by checkpoints).
MapField done_field();
// The per-cell datasets in file order: status, regime, stable, n, k, wall_s, steady_residual,
// then the stored quantities; with a census (attractors > 0), attractors, soft_fraction,
// unresolved_fraction, unlisted_fraction, budget_fraction, basin_entropy and the attractor_*
// datasets (slots = attractors).
// With refine_levels > 0 (an adaptive map), then computed and level (int8, -1 where not decided).
// With shock (census.shock), the shock fields per (cell, attractor); with fragility, then fragile
// (int8, -1 where not assessed).
std::vector<MapField> map_fields(const std::vector<Quantity>& stored, std::size_t attractors, int refine_levels = 0,
                                 bool shock = false, bool fragility = false);
// The datasets of a map of `layout`.
std::vector<MapField> map_fields(const MapLayout& layout);
std::uint64_t element_bytes(ElementType t);
// Period-start states per attractor that a census map keeps (/attractor_strobe): the first ones
// of each orbit, NaN past its period.
constexpr std::size_t kMapStrobePoints = 4;
// The family datasets of a census map (/family, /family_flags; slots = attractors): made with
// the map, filled by the family pass (io/map_families.hpp), not CellResult members (no
// accessors: a cell's write leaves them alone).
std::vector<MapField> family_fields(std::size_t attractors);

// The chunks of an N-D map dataset of `shape`: trailing axes whole while they fit in
// kMapChunkCells cells, then as many slices of the next axis as fit (at least one), 1 before.
// Every chunk is then a contiguous range of flat indices.
Shape map_chunk_shape(const Shape& shape);
// Every chunk of `shape` as its range of flat indices, in flat order.
std::vector<CellSpan> chunk_spans(const Shape& shape, const Shape& chunk);

}  // namespace vibromap::detail
