#pragma once
// A small checked C++ layer over the HDF5 C library, in the spirit of HighFive: one RAII
// handle type that closes every hid_t with its own H5*close, one checking helper that turns a
// negative return into vibromap::IoError, and no raw H5* call outside src/io/hdf5_file.cpp and
// its two halves hdf5_dataset.cpp (datasets, groups) and hdf5_listing.cpp (listing a file).
//
// This header does not include <hdf5.h>: HDF5 stays a private dependency of vibromap::io, and
// code that reads or writes files (tests, sweep output) needs no HDF5 include path.
// detail::Hid is HDF5's hid_t (int64_t since 1.10; a static_assert in the .cpp checks it).
//
// Errors: every failed call throws IoError with one line "<file>: cannot <operation> (<HDF5's
// innermost reason>)". HDF5's automatic error-stack printing is switched off the first time a
// file is opened, so nothing else reaches stderr.
//
// Data layout: arrays are row-major (C order, as in HDF5, numpy and h5py); a Shape lists the
// extent of each dimension, slowest first. Doubles are stored as IEEE float64 little-endian,
// integers as 64-, 32- or 8-bit signed or 8-bit unsigned little-endian, strings as
// variable-length UTF-8 (h5py reads them back as str). Reading converts between numeric types
// as HDF5 does.
//
// netCDF-4: files, groups and datasets are created with link and attribute creation order
// tracked and indexed, as netCDF-C creates its own. netCDF-C 4.9 opens files without it too,
// but then lists variables and attributes by name; with it, netCDF4-python and xarray list them
// in the order written, and older netCDF-C versions that expect the index find it. Dimension
// scales (HDF5 High-Level H5DS) name a dataset's dimensions: netCDF and xarray read them as
// named dimensions with coordinates.

#include <cstddef>
#include <concepts>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vibromap {

// The one exception type of the I/O layer: a failed file operation, or a file whose content
// is not what the reader expects. what() is one line naming the file and the operation.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Extent of each dimension of a dataset, slowest-varying first (row-major).
using Shape = std::vector<std::size_t>;

namespace detail {

using Hid = std::int64_t;  // hid_t

enum class HandleKind { file, group, dataset, dataspace, datatype, attribute, property_list };

// Owns one HDF5 identifier and closes it with the H5*close that matches its kind. Move-only.
// The destructor ignores a failing close (it may run during unwinding); File::close() is the
// checked way to close a file.
class Handle {
 public:
  Handle() = default;
  Handle(Hid id, HandleKind kind) noexcept : id_(id), kind_(kind) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_), kind_(other.kind_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  Hid get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  HandleKind kind() const { return kind_; }
  void reset() noexcept;  // closes, ignoring errors
  Hid release() noexcept {
    const Hid id = id_;
    id_ = -1;
    return id;
  }

 private:
  Hid id_ = -1;
  HandleKind kind_ = HandleKind::file;
};

// The checking helper: returns `ret` when it is >= 0, else throws IoError
// "<file>: cannot <operation> (<reason from HDF5's error stack>)" and clears the stack.
// Used for hid_t, herr_t and htri_t returns alike.
std::int64_t check(std::int64_t ret, std::string_view file, std::string_view operation);

// Throws IoError "<file>: <message>" (for checks that are ours, not HDF5's).
[[noreturn]] void fail(std::string_view file, std::string_view message);

}  // namespace detail

// The element types of datasets (file types little-endian; integers signed but uint8).
enum class ElementType { float64, int64, int32, int8, uint8 };

// One attribute's value as stored, for comparing a file with itself (attribute checksums,
// attribute_seal.hpp): a string as its bytes, integers as int64, floats as float64, anything
// else (a compound, a reference) by its HDF5 type class alone.
struct AttributeValue {
  enum class Kind { string, integer, real, other };
  Kind kind = Kind::other;
  std::string text;                // string: its bytes (a fixed-length one without trailing NULs)
  std::vector<std::int64_t> ints;  // integer: every element, flattened
  std::vector<double> reals;       // real: every element, flattened
  int type_class = -1;             // other: HDF5's H5T_class_t of the attribute
};

// What a link in a group leads to.
enum class LinkKind { group, dataset, other };

// Storage options of a new dataset. Defaults: contiguous, uncompressed.
struct DatasetOptions {
  Shape chunk;      // chunk extent per dimension (clamped to the data's extent); empty: contiguous unless deflate > 0 or fletcher32, -
  int deflate = 0;  // gzip level 1..9 (needs chunks: the whole array is one chunk if chunk is empty); 0: none, -
  // Value of elements never written, converted to the dataset's type; also written as the
  // attribute "_FillValue" of the dataset's own type (the netCDF/CF convention, which
  // xarray decodes to NaN). Empty: HDF5's default (0) and no attribute, -
  std::optional<double> fill_value = std::nullopt;  // (initialised: aggregates may omit it without a warning)
  // Write fill_value also as the attribute "_FillValue" (xarray then masks it to NaN: right for
  // floats, not for integer codes whose fill is itself a meaning, such as -1 "not computed"), -
  bool fill_attribute = true;
  // HDF5's Fletcher32 checksum filter on every chunk (h5py and netCDF-4 verify it on each read):
  // a damaged byte makes the read of its chunk fail instead of returning a wrong number, -
  bool fletcher32 = false;
  // Allocate every chunk (and write its fill value) when the dataset is made, so that writes
  // never change the file's structure (nor its size), -
  bool allocate_early = false;
};

// Something that carries attributes: the file's root group, a group or a dataset. Holds its
// handle, the file's path (for messages) and its own name inside the file.
class Hdf5Object {
 public:
  // Creates or replaces a scalar attribute: a string, a double (float64) or an integer
  // (int64). bool is refused: write 0 or 1 so the reader sees a number.
  void set_attribute(std::string_view name, std::string_view value);
  void set_attribute(std::string_view name, const char* value) { set_attribute(name, std::string_view(value)); }
  void set_attribute(std::string_view name, const std::string& value) { set_attribute(name, std::string_view(value)); }
  void set_attribute(std::string_view name, double value);
  template <std::integral T>
  void set_attribute(std::string_view name, T value) {
    set_int_attribute(name, static_cast<std::int64_t>(value));
  }
  void set_attribute(std::string_view name, bool value) = delete;
  // Creates or replaces a 1-D array attribute of int8 or float64 elements (CF flag_values,
  // valid_range). An empty array is refused (HDF5 cannot store it as a simple dataspace).
  void set_attribute(std::string_view name, std::span<const std::int8_t> values);
  void set_attribute(std::string_view name, std::span<const double> values);

  bool has_attribute(std::string_view name) const;
  // Read a scalar attribute (a 1-element array is accepted); throw IoError when it is
  // missing or of another kind (numeric types convert among themselves).
  double read_double_attribute(std::string_view name) const;
  std::int64_t read_int_attribute(std::string_view name) const;
  std::string read_string_attribute(std::string_view name) const;
  // Read a numeric attribute of any extent (a scalar reads as one element), flattened.
  std::vector<std::int64_t> read_int_array_attribute(std::string_view name) const;
  std::vector<double> read_double_array_attribute(std::string_view name) const;
  // The names of the attributes, sorted by their bytes; and one attribute's value as stored
  // (hdf5_listing.cpp). Both throw IoError when HDF5 cannot read them (a damaged file).
  std::vector<std::string> attribute_names() const;
  AttributeValue read_attribute(std::string_view name) const;
  // Removes an attribute (nothing when there is none).
  void remove_attribute(std::string_view name);

  const std::string& name() const { return name_; }  // path inside the file, "/" for the root
  detail::Hid id() const { return handle_.get(); }

 protected:
  Hdf5Object() = default;
  Hdf5Object(detail::Handle handle, std::string file_path, std::string name)
      : handle_(std::move(handle)), file_path_(std::move(file_path)), name_(std::move(name)) {}
  std::string child_name(std::string_view child) const;  // "/a" + "b" -> "/a/b"
  void set_int_attribute(std::string_view name, std::int64_t value);
  void set_array_attribute(std::string_view name, const void* values, std::size_t count, bool as_int8);
  void read_array_attribute(std::string_view name, void* out, std::size_t count, bool as_double) const;
  std::size_t attribute_size(std::string_view name) const;

  detail::Handle handle_;
  std::string file_path_;
  std::string name_;
};

// A dataset: an N-D array of numbers. Reads return the whole array flattened row-major.
// Dimension scales (HDF5 H5DS, the netCDF-4 form of a coordinate): a 1-D dataset made a scale
// named after its dimension is attached to dimension `dim` of each dataset it labels.
class Dataset : public Hdf5Object {
 public:
  Dataset() = default;
  Shape shape() const;
  std::size_t size() const;  // number of elements
  std::vector<double> read_double() const;
  std::vector<std::int64_t> read_int() const;
  Shape chunk_shape() const;         // empty when the dataset is not chunked

  // The elements [first, first + values.size()) in flat (row-major) order, as one selection
  // of at most 2N-1 boxes of the N-D dataset; converted to and from the dataset's own type.
  template <class T>
  void write_flat(std::uint64_t first, std::span<const T> values);
  template <class T>
  void read_flat(std::uint64_t first, std::span<T> values) const;
  // Replaces the whole chunk that starts at `offset` (one index per dimension, a multiple of the
  // chunk extent) with `fill` (converted to the dataset's type), written directly as stored
  // bytes (H5Dwrite_chunk) with its Fletcher32 checksum when the dataset has one: the old chunk
  // is never read, so a damaged one (its checksum failing) can be replaced, an edge chunk that
  // overhangs the dataset included. Only for datasets without filters but Fletcher32.
  void reset_chunk(const Shape& offset, double fill);

  // Makes this dataset a dimension scale whose dimension is called `dimension_name`
  // (netCDF reads a scale named after its own dataset as a coordinate variable).
  void make_dimension_scale(std::string_view dimension_name);
  // Attaches the dimension scale `scale` to dimension `dim` of this dataset.
  void attach_dimension_scale(const Dataset& scale, std::size_t dim);
  bool is_dimension_scale() const;
  std::string dimension_scale_name() const;  // the name given by make_dimension_scale; "" if none
  // Paths ("/E1") of the scales attached to dimension `dim`, in the order attached.
  std::vector<std::string> attached_scales(std::size_t dim) const;
  // The element type as numpy spells it ("<f8", "|i1", "|u1", "<i4", ">f8"...; "other" for a
  // type that is not an integer or a float), for comparing a file with itself (hdf5_listing.cpp).
  std::string element_type_text() const;
  // Whether the chunk that starts at `offset` (one index per dimension, a multiple of the chunk
  // extent) is in the chunk index, looked up as a read looks it up (hdf5_listing.cpp). In a
  // dataset allocated early (DatasetOptions::allocate_early) a chunk not there means a damaged
  // index, which HDF5 would read as fill values without any error.
  bool chunk_allocated(const Shape& offset) const;

 private:
  friend class Group;
  using Hdf5Object::Hdf5Object;
  void read_into(void* buffer, std::size_t count, bool as_double) const;
  void transfer_flat(std::uint64_t first, std::size_t count, ElementType memory, void* buffer, bool write) const;
};

template <class T>
constexpr ElementType element_type_of() {
  if constexpr (std::is_same_v<T, double>) return ElementType::float64;
  else if constexpr (std::is_same_v<T, std::int64_t>) return ElementType::int64;
  else if constexpr (std::is_same_v<T, std::int32_t>) return ElementType::int32;
  else if constexpr (std::is_same_v<T, std::int8_t>) return ElementType::int8;
  else {
    static_assert(std::is_same_v<T, std::uint8_t>, "float64, int64, int32, int8 or uint8");
    return ElementType::uint8;
  }
}

template <class T>
void Dataset::write_flat(std::uint64_t first, std::span<const T> values) {
  transfer_flat(first, values.size(), element_type_of<T>(), const_cast<T*>(values.data()), true);
}

template <class T>
void Dataset::read_flat(std::uint64_t first, std::span<T> values) const {
  transfer_flat(first, values.size(), element_type_of<T>(), values.data(), false);
}

// A group: a directory of datasets and groups (the file's root is one).
// write_dataset creates a new dataset (throws if `name` exists); an empty shape means 1-D
// with data.size() elements, otherwise the product of shape must equal data.size().
class Group : public Hdf5Object {
 public:
  Dataset write_dataset(std::string_view name, std::span<const double> data, const Shape& shape = {},
                        const DatasetOptions& options = {});
  Dataset write_dataset(std::string_view name, std::span<const std::int64_t> data, const Shape& shape = {},
                        const DatasetOptions& options = {});
  Dataset write_dataset(std::string_view name, std::span<const int> data, const Shape& shape = {},
                        const DatasetOptions& options = {});
  Dataset write_dataset(std::string_view name, std::span<const std::int8_t> data, const Shape& shape = {},
                        const DatasetOptions& options = {});
  Dataset write_dataset(std::string_view name, std::span<const std::uint8_t> data, const Shape& shape = {},
                        const DatasetOptions& options = {});
  // A 1-D dataset of variable-length UTF-8 strings (netCDF-4's string type).
  Dataset write_strings(std::string_view name, std::span<const std::string> values);
  // A new dataset of `shape` holding only fill values (write it with Dataset::write_flat).
  Dataset create_dataset(std::string_view name, ElementType type, const Shape& shape, const DatasetOptions& options);
  Dataset open_dataset(std::string_view name) const;

  Group create_group(std::string_view name);
  Group open_group(std::string_view name) const;
  bool exists(std::string_view name) const;  // a link `name` (dataset or group) exists here
  // The links of this group (names sorted by their bytes) and what each leads to
  // (hdf5_listing.cpp); soft and external links are `other`. Throws IoError.
  std::vector<std::pair<std::string, LinkKind>> links() const;
  // Reads the header of every object reachable from this group, all its chunks with their
  // checksums (hdf5_listing.cpp): a header HDF5 cannot read throws IoError, so a file whose
  // data reads but whose object headers are damaged is not taken as whole.
  void check_object_headers() const;
  // Removes the link `name` (a dataset or group); HDF5 does not reclaim its space in the file.
  void remove(std::string_view name);

 protected:
  using Hdf5Object::Hdf5Object;

 private:
  Dataset write_numbers(std::string_view name, const void* data, std::size_t count, ElementType element,
                        const Shape& shape, const DatasetOptions& options);
};

enum class FileMode {
  truncate,    // create, replacing an existing file
  read_write,  // open an existing file for reading and writing
  read_only,   // open an existing file for reading
};

// How a file is opened. Defaults: what every reader expects.
struct FileOptions {
  // HDF5's own file lock (flock) while the file is open. Off for a file written over hours
  // that readers should be able to open meanwhile (the writer keeps a lock of its own), -
  bool locking = true;
  // Raw-data chunk cache per dataset, bytes (HDF5's default is 1 MiB), -
  std::size_t chunk_cache_bytes = 1 << 20;
  // Write the 1.8 file format (checksummed object headers; netCDF-4 and h5py read it) instead
  // of the oldest one that can hold the file, -
  bool format_1_8 = false;
};

// An open HDF5 file, usable as its root group "/". Move-only; the destructor closes it.
class Hdf5File : public Group {
 public:
  explicit Hdf5File(const std::string& path, FileMode mode = FileMode::read_only, const FileOptions& options = {});

  const std::string& path() const { return file_path_; }
  void flush();
  // flush(), then the operating system's buffers of the file to the disk (fsync).
  void sync();
  // Starts writing the operating system's buffers of the file to the disk, without waiting
  // (sync_file_range): a sync() soon after has less to wait for. Best effort: never throws.
  void start_writeback();
  int descriptor() const;  // the file's POSIX descriptor (sec2 driver)
  // Closes the file and reports a failure (e.g. a failed final flush) as IoError. Objects
  // opened from this file must be destroyed first: HDF5 keeps the file open until they are.
  void close();
};

// Writes the HDF5 file `path` atomically: `fill` writes into a new file beside it (NewFile,
// io/output_file.hpp: created exclusively, never through a link), which is closed, synced to
// the disk and renamed over `path` only when fill returns. On any exception (from fill, HDF5,
// the close or the rename) the new file is removed, an existing `path` is left untouched, and
// the exception propagates. An existing `path` that is not a regular file is refused.
void write_hdf5_atomically(const std::string& path, const std::function<void(Hdf5File&)>& fill);

}  // namespace vibromap
