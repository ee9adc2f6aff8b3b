#pragma once
// Internal to the map file: its on-disk layout (map_file.hpp documents it), made and read back
// here (map_layout.cpp), and one chunk of every dataset in memory (MapDatasets). MapWriter and
// the whole-map readers (map_file.cpp) build on these.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "map_fields.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap::detail {

constexpr std::uint64_t kDoneWindow = 1u << 20;  // cells of /done read or set at a time

// How maps are opened: no HDF5 file locking (readers may open a map while it runs; the sweep
// holds its own lock), a chunk cache of a few chunks per dataset.
FileOptions writer_options();
// Throws IoError "<path>: not a valid vibromap map: <what>".
[[noreturn]] void malformed(const std::string& path, std::string_view what);

// ---- Making a map
// Refuses, before any file is touched, a layout the file cannot hold (no axes, repeated names).
void check_layout(const std::string& path, const MapLayout& layout);
// The axes' coordinate datasets, made dimension scales, in axis order.
std::vector<Dataset> write_axes(Hdf5File& file, const Grid& grid);
// The census's attractor index 0..A-1 as a coordinate.
Dataset write_attractor_scale(Hdf5File& file, std::size_t attractors);
// A census map's coordinates after the axes: /attractor, /period_start (kMapStrobePoints) and
// /state (x1 x2 v1 v2), appended to `scales` in that order.
void write_census_scales(Hdf5File& file, std::size_t attractors, std::vector<Dataset>& scales);
// The shape of field f's dataset: the grid's, with one more dimension per (cell, attractor) field.
Shape with_slots(Shape shape, const MapField& f);
// Field f's dataset, chunked as the cells' `chunk`, with its attributes; `scales`: the axes'
// coordinates, then (with a census) /attractor.
Dataset make_field(Hdf5File& file, const MapField& f, const Shape& shape, const Shape& chunk,
                   const std::vector<Dataset>& scales);
// The root attributes, then the seal over every attribute (attribute_seal.hpp): call it last.
void write_root_attributes(Hdf5File& file, const MapLayout& layout, int ranks);

// ---- Reading a map's layout
// Its axes, stored quantities, scene, identity and attractor dimension; malformed() when a
// required part is missing or inconsistent. The format version and the attributes' seal are
// checked first (verify_file): a map of another version is refused as such (FileVersionError),
// and damage is reported as damage ("<path>: damaged: ..."), never as a wrong value.
MapLayout read_layout(const Hdf5File& file);

// ---- One chunk of every dataset
// The datasets of an open map and a buffer per dataset for one chunk of cells.
struct MapDatasets {
  std::vector<MapField> fields;
  Dataset done;
  std::vector<Dataset> data;                     // fields[i]'s dataset
  std::vector<std::uint8_t> done_buffer;
  std::vector<std::vector<double>> reals;        // per field, float fields
  std::vector<std::vector<std::int64_t>> ints;   // per field, integer fields
  Shape grid_shape;                              // the grid's shape, read from /done by read()

  // Opens every dataset of `layout` in `file`, checking its shape.
  void open(const Hdf5File& file, const MapLayout& layout);
  // Reads cells `span` of dataset i (-1: done). False when HDF5 fails (a damaged chunk), or when
  // the chunk is missing from the dataset's chunk index (a damaged index: HDF5 would read fill
  // values without an error, but every chunk of a map is allocated when it is made).
  bool read(int i, const CellSpan& span, std::string* why);
  // Chunk `span` of dataset i (-1: done) is not in its chunk index (maps allocate every chunk).
  bool chunk_missing(int i, const CellSpan& span);
  std::string name(int i) const { return i < 0 ? "done" : fields[static_cast<std::size_t>(i)].name; }
  // Cell k of the chunk read last, from the buffers (integer values range-checked).
  CellResult cell(std::size_t k, const std::string& path) const;
  // Replaces chunk `span` of every dataset with fill values, /done with 0, without reading it.
  void fill_chunk(const CellSpan& span, const Shape& shape);
};

}  // namespace vibromap::detail
