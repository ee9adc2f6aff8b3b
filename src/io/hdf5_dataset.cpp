// The Dataset and Group parts of the checked HDF5 layer (hdf5_file.hpp): creating and writing
// datasets, flat ranges of N-D datasets, direct chunk writes, dimension scales, groups.

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cstring>

#include "hdf5_internal.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {

using detail::check;
using detail::fail;
using detail::Handle;
using detail::HandleKind;

// ---- Dataset ----------------------------------------------------------------------------

Shape Dataset::shape() const {
  const std::string what = detail::describe("dataset", name_);
  const Handle space = detail::make_handle(H5Dget_space(id()), HandleKind::dataspace, file_path_,
                                           "get the dataspace of " + what);
  const auto rank = check(H5Sget_simple_extent_ndims(space.get()), file_path_, "get the rank of " + what);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), file_path_, "get the shape of " + what);
  return Shape(dims.begin(), dims.end());
}

std::size_t Dataset::size() const {
  const std::string what = detail::describe("dataset", name_);
  const Handle space = detail::make_handle(H5Dget_space(id()), HandleKind::dataspace, file_path_,
                                           "get the dataspace of " + what);
  return detail::element_count(space.get(), file_path_, what);
}

void Dataset::read_into(void* buffer, std::size_t count, bool as_double) const {
  const std::string what = detail::describe("dataset", name_);
  const Handle type = detail::make_handle(H5Dget_type(id()), HandleKind::datatype, file_path_, "get the type of " + what);
  const H5T_class_t c = detail::type_class(type.get(), file_path_, what);
  if (c != H5T_INTEGER && (!as_double || c != H5T_FLOAT))
    fail(file_path_, what + (as_double ? " is not numeric" : " is not an integer array"));
  if (count == 0) return;  // HDF5 rejects a null buffer even for nothing to read
  check(H5Dread(id(), as_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer),
        file_path_, "read " + what);
}

std::vector<double> Dataset::read_double() const {
  std::vector<double> data(size());
  read_into(data.data(), data.size(), true);
  return data;
}

std::vector<std::int64_t> Dataset::read_int() const {
  std::vector<std::int64_t> data(size());
  read_into(data.data(), data.size(), false);
  return data;
}

Shape Dataset::chunk_shape() const {
  const std::string what = detail::describe("dataset", name_);
  const Handle dcpl = detail::make_handle(H5Dget_create_plist(id()), HandleKind::property_list, file_path_,
                                          "get the creation properties of " + what);
  if (H5Pget_layout(dcpl.get()) != H5D_CHUNKED) return {};
  std::vector<hsize_t> dims(shape().size());
  check(H5Pget_chunk(dcpl.get(), static_cast<int>(dims.size()), dims.data()), file_path_, "get the chunks of " + what);
  return Shape(dims.begin(), dims.end());
}

namespace {

// Adds to `space` the boxes that hold the flat (row-major) elements [first, last) of an array
// of extent dims[d..] whose leading indices are prefix[0..d): at most 2(N-d)-1 boxes.
void select_flat(hid_t space, const std::vector<hsize_t>& dims, std::size_t d, std::vector<hsize_t>& start,
                 hsize_t first, hsize_t last, bool& any, const std::string& file) {
  if (first >= last) return;
  hsize_t inner = 1;
  for (std::size_t i = d + 1; i < dims.size(); ++i) inner *= dims[i];
  const hsize_t lo = first / inner, hi = (last - 1) / inner;  // the slices of dimension d touched
  if (lo == hi && d + 1 < dims.size()) {
    start[d] = lo;
    select_flat(space, dims, d + 1, start, first - lo * inner, last - lo * inner, any, file);
    return;
  }
  hsize_t full_lo = lo, full_hi = hi + 1;  // slices of dimension d covered whole: [full_lo, full_hi)
  if (first % inner != 0) {
    start[d] = lo;
    select_flat(space, dims, d + 1, start, first - lo * inner, inner, any, file);
    ++full_lo;
  }
  if (last % inner != 0 && hi >= full_lo) {
    start[d] = hi;
    select_flat(space, dims, d + 1, start, 0, last - hi * inner, any, file);
    --full_hi;
  }
  if (full_lo >= full_hi) return;
  std::vector<hsize_t> box_start(start.begin(), start.end()), count(dims.size(), 1);
  box_start[d] = full_lo;
  count[d] = full_hi - full_lo;
  for (std::size_t i = d + 1; i < dims.size(); ++i) box_start[i] = 0, count[i] = dims[i];
  check(H5Sselect_hyperslab(space, any ? H5S_SELECT_OR : H5S_SELECT_SET, box_start.data(), nullptr, count.data(),
                            nullptr),
        file, "select a range of elements");
  any = true;
}

}  // namespace

void Dataset::transfer_flat(std::uint64_t first, std::size_t count, ElementType memory, void* buffer, bool write) const {
  const std::string what = detail::describe("dataset", name_);
  const std::string operation = cat(write ? "write " : "read ", what, " elements ", std::to_string(first), "..",
                                    std::to_string(first + count));
  if (count == 0) return;
  Handle space = detail::make_handle(H5Dget_space(id()), HandleKind::dataspace, file_path_, "get the dataspace of " + what);
  const int rank = static_cast<int>(check(H5Sget_simple_extent_ndims(space.get()), file_path_, "get the rank of " + what));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  check(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr), file_path_, "get the shape of " + what);
  hsize_t total = 1;
  for (const hsize_t n : dims) total *= n;
  if (first + count > total) fail(file_path_, cat("cannot ", operation, ": the dataset holds ", std::to_string(total)));
  std::vector<hsize_t> start(dims.size(), 0);
  bool any = false;
  select_flat(space.get(), dims, 0, start, first, first + count, any, file_path_);
  // One box (a chunk of a map, a run within a row): the memory takes the box's shape, the same
  // elements in the same order, which HDF5 maps onto the chunks box by box; a flat memory space
  // it would map element by element (whole chunks of a map written or read: twice as slow).
  std::vector<hsize_t> mem_dims{static_cast<hsize_t>(count)};
  if (rank > 1) {
    std::vector<hsize_t> lo(dims.size()), hi(dims.size());
    check(H5Sget_select_bounds(space.get(), lo.data(), hi.data()), file_path_, "get the bounds of a selection of " + what);
    hsize_t box = 1;
    for (std::size_t d = 0; d < dims.size(); ++d) box *= (lo[d] = hi[d] - lo[d] + 1);
    if (box == count) mem_dims = lo;  // the selection is its bounding box
  }
  const Handle memspace = detail::make_handle(H5Screate_simple(static_cast<int>(mem_dims.size()), mem_dims.data(), nullptr),
                                              HandleKind::dataspace, file_path_, "create a memory dataspace for " + what);
  const hid_t mem_type = detail::element_types(memory).second;
  if (write) {
    check(H5Dwrite(id(), mem_type, memspace.get(), space.get(), H5P_DEFAULT, buffer), file_path_, operation);
  } else {
    check(H5Dread(id(), mem_type, memspace.get(), space.get(), H5P_DEFAULT, buffer), file_path_, operation);
  }
}

namespace {

// HDF5's Fletcher32 (H5checksum.c, H5_checksum_fletcher32): 16-bit words taken big-endian,
// sums folded every 360 words, an odd last byte as the high byte of a word.
std::uint32_t fletcher32(const unsigned char* data, std::size_t bytes) {
  std::size_t words = bytes / 2;
  std::uint32_t sum1 = 0, sum2 = 0;
  while (words > 0) {
    std::size_t block = std::min<std::size_t>(words, 360);
    words -= block;
    do {
      sum1 += (static_cast<std::uint32_t>(data[0]) << 8) | data[1];
      data += 2;
      sum2 += sum1;
    } while (--block);
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  if (bytes % 2) {
    sum1 += static_cast<std::uint32_t>(*data) << 8;
    sum2 += sum1;
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  }
  sum1 = (sum1 & 0xffff) + (sum1 >> 16);
  sum2 = (sum2 & 0xffff) + (sum2 >> 16);
  return (sum2 << 16) | sum1;
}

}  // namespace

void Dataset::reset_chunk(const Shape& offset, double fill) {
  const std::string what = detail::describe("dataset", name_);
  const std::string operation = "replace a chunk of " + what;
  const Shape chunk = chunk_shape();
  if (chunk.size() != offset.size()) fail(file_path_, cat("cannot ", operation, ": not chunked as expected"));
  const Handle dcpl = detail::make_handle(H5Dget_create_plist(id()), HandleKind::property_list, file_path_,
                                          "get the creation properties of " + what);
  const int filters = static_cast<int>(check(H5Pget_nfilters(dcpl.get()), file_path_, operation));
  bool checksum = false;
  for (int i = 0; i < filters; ++i) {
    unsigned flags = 0;
    std::size_t n = 0;
    const H5Z_filter_t f = H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags, &n, nullptr, 0, nullptr, nullptr);
    if (f != H5Z_FILTER_FLETCHER32) fail(file_path_, cat("cannot ", operation, ": it has a filter other than Fletcher32"));
    checksum = true;
  }
  std::size_t elements = 1;
  for (const std::size_t c : chunk) elements *= c;
  // The fill value in the file's own type, as HDF5 stores it (little-endian types only).
  const Handle type = detail::make_handle(H5Dget_type(id()), HandleKind::datatype, file_path_, "get the type of " + what);
  const std::size_t size = H5Tget_size(type.get());
  std::vector<unsigned char> convert(std::max<std::size_t>(size, sizeof(double)));
  std::memcpy(convert.data(), &fill, sizeof fill);
  check(H5Tconvert(H5T_NATIVE_DOUBLE, type.get(), 1, convert.data(), nullptr, H5P_DEFAULT), file_path_,
        "convert the fill value of " + what);
  std::vector<unsigned char> bytes(elements * size + (checksum ? 4 : 0));
  for (std::size_t i = 0; i < elements; ++i) std::memcpy(bytes.data() + i * size, convert.data(), size);
  if (checksum) {
    const std::uint32_t sum = fletcher32(bytes.data(), elements * size);
    for (int k = 0; k < 4; ++k) bytes[elements * size + static_cast<std::size_t>(k)] = static_cast<unsigned char>(sum >> (8 * k));
  }
  std::vector<hsize_t> at(offset.begin(), offset.end());
  check(H5Dwrite_chunk(id(), H5P_DEFAULT, 0, at.data(), bytes.size(), bytes.data()), file_path_, operation);
}

// ---- Dataset: dimension scales (HDF5 High-Level H5DS) -----------------------------------

void Dataset::make_dimension_scale(std::string_view dimension_name) {
  check(H5DSset_scale(id(), std::string(dimension_name).c_str()), file_path_,
        cat("make ", detail::describe("dataset", name_), " a dimension scale"));
}

void Dataset::attach_dimension_scale(const Dataset& scale, std::size_t dim) {
  const std::string operation = cat("attach ", detail::describe("dimension scale", scale.name()), " to ",
                                            detail::describe("dataset", name_), " dimension ", std::to_string(dim));
  if (dim >= shape().size()) fail(file_path_, cat("cannot ", operation, ": no such dimension"));
  check(H5DSattach_scale(id(), scale.id(), static_cast<unsigned>(dim)), file_path_, operation);
}

bool Dataset::is_dimension_scale() const {
  return check(H5DSis_scale(id()), file_path_, cat("inspect ", detail::describe("dataset", name_))) > 0;
}

std::string Dataset::dimension_scale_name() const {
  if (!is_dimension_scale()) return {};
  const std::string operation = cat("get the dimension name of ", detail::describe("dataset", name_));
  const auto length = check(H5DSget_scale_name(id(), nullptr, 0), file_path_, operation);
  if (length == 0) return {};
  std::vector<char> buffer(static_cast<std::size_t>(length) + 1, '\0');
  check(H5DSget_scale_name(id(), buffer.data(), buffer.size()), file_path_, operation);
  return std::string(buffer.data());
}

std::vector<std::string> Dataset::attached_scales(std::size_t dim) const {
  const std::string operation = cat("list the dimension scales of ", detail::describe("dataset", name_),
                                            " dimension ", std::to_string(dim));
  if (dim >= shape().size()) fail(file_path_, cat("cannot ", operation, ": no such dimension"));
  // H5DSiterate_scales calls back with each attached scale; its path comes from H5Iget_name.
  const auto visit = [](hid_t, unsigned, hid_t scale, void* data) -> herr_t {
    const ssize_t length = H5Iget_name(scale, nullptr, 0);
    if (length < 0) return -1;
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    if (H5Iget_name(scale, name.data(), name.size()) < 0) return -1;
    name.resize(static_cast<std::size_t>(length));
    static_cast<std::vector<std::string>*>(data)->push_back(std::move(name));
    return 0;
  };
  std::vector<std::string> names;
  const int count = static_cast<int>(check(H5DSget_num_scales(id(), static_cast<unsigned>(dim)), file_path_, operation));
  if (count == 0) return names;
  check(H5DSiterate_scales(id(), static_cast<unsigned>(dim), nullptr, visit, &names), file_path_, operation);
  return names;
}

// ---- Group ------------------------------------------------------------------------------

namespace {

// The dataset creation property list for `options` (chunking and gzip), checked against dims.
Handle dataset_creation_list(const std::vector<hsize_t>& dims, std::size_t count, const DatasetOptions& options,
                             const std::string& file, const std::string& what) {
  Handle dcpl = detail::make_handle(H5Pcreate(H5P_DATASET_CREATE), HandleKind::property_list, file,
                                    "create property list for " + what);
  if (options.deflate < 0 || options.deflate > 9) fail(file, what + ": deflate level must be 0..9");
  if (!options.chunk.empty() && options.chunk.size() != dims.size())
    fail(file, what + ": chunk rank differs from the data's rank");
  detail::track_creation_order(dcpl.get(), false, file);
  // No modification times in object headers: the same content gives the same bytes, and
  // writing data never touches a header.
  check(H5Pset_obj_track_times(dcpl.get(), 0), file, "switch off time tracking for " + what);
  if (options.fill_value)
    check(H5Pset_fill_value(dcpl.get(), H5T_NATIVE_DOUBLE, &*options.fill_value), file, "set the fill value of " + what);
  if (options.allocate_early) {
    check(H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY), file, "set early allocation for " + what);
    check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_ALLOC), file, "set the fill time of " + what);
  }
  // HDF5 cannot chunk a fixed-size array with an empty dimension; nothing to compress anyway.
  if (count == 0 || (options.chunk.empty() && options.deflate == 0 && !options.fletcher32)) return dcpl;
  std::vector<hsize_t> chunk(dims.size());
  for (std::size_t i = 0; i < dims.size(); ++i) {
    const hsize_t wanted = options.chunk.empty() ? dims[i] : static_cast<hsize_t>(options.chunk[i]);
    chunk[i] = std::max<hsize_t>(1, std::min(wanted, dims[i]));
  }
  check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), file, "set chunks for " + what);
  if (options.deflate > 0)
    check(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(options.deflate)), file, "set compression for " + what);
  if (options.fletcher32) check(H5Pset_fletcher32(dcpl.get()), file, "set the checksum filter for " + what);
  return dcpl;
}

}  // namespace


Dataset Group::write_numbers(std::string_view name, const void* data, std::size_t count, ElementType element,
                             const Shape& shape, const DatasetOptions& options) {
  const std::string full_name = child_name(name);
  const std::string what = detail::describe("dataset", full_name);
  std::vector<hsize_t> dims;
  if (shape.empty()) {
    dims.push_back(count);
  } else {
    std::size_t product = 1;
    for (const std::size_t d : shape) {
      dims.push_back(d);
      product *= d;
    }
    if (product != count)
      fail(file_path_, cat("cannot write ", what, ": shape holds ", std::to_string(product),
                                   " values, data has ", std::to_string(count)));
  }
  const auto [file_type, mem_type] = detail::element_types(element);
  const Handle space = detail::make_handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                                           HandleKind::dataspace, file_path_, "create dataspace for " + what);
  const Handle dcpl = dataset_creation_list(dims, count, options, file_path_, what);
  const Handle lcpl = detail::link_creation_list(file_path_);
  Handle dataset = detail::make_handle(
      H5Dcreate2(id(), std::string(name).c_str(), file_type, space.get(), lcpl.get(), dcpl.get(), H5P_DEFAULT),
      HandleKind::dataset, file_path_, "create " + what);
  if (count > 0 && data != nullptr)
    check(H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file_path_, "write " + what);
  if (options.fill_value && options.fill_attribute)
    detail::write_attribute(dataset.get(), "_FillValue", file_path_, file_type, H5T_NATIVE_DOUBLE, &*options.fill_value);
  return Dataset(std::move(dataset), file_path_, full_name);
}

Dataset Group::create_dataset(std::string_view name, ElementType type, const Shape& shape,
                              const DatasetOptions& options) {
  std::size_t count = 1;
  for (const std::size_t d : shape) count *= d;
  return write_numbers(name, nullptr, count, type, shape.empty() ? Shape{0} : shape, options);
}

Dataset Group::write_strings(std::string_view name, std::span<const std::string> values) {
  const std::string full_name = child_name(name);
  const std::string what = detail::describe("dataset", full_name);
  const hsize_t dims[1] = {values.size()};
  const Handle type = detail::vlen_string_type(file_path_);
  const Handle space = detail::make_handle(H5Screate_simple(1, dims, nullptr), HandleKind::dataspace, file_path_,
                                           "create dataspace for " + what);
  const Handle lcpl = detail::link_creation_list(file_path_);
  Handle dataset = detail::make_handle(
      H5Dcreate2(id(), std::string(name).c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
      HandleKind::dataset, file_path_, "create " + what);
  std::vector<const char*> data;
  for (const std::string& v : values) data.push_back(v.c_str());
  if (!data.empty())
    check(H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), file_path_, "write " + what);
  return Dataset(std::move(dataset), file_path_, full_name);
}

Dataset Group::write_dataset(std::string_view name, std::span<const double> data, const Shape& shape,
                             const DatasetOptions& options) {
  return write_numbers(name, data.data(), data.size(), ElementType::float64, shape, options);
}

Dataset Group::write_dataset(std::string_view name, std::span<const std::int64_t> data, const Shape& shape,
                             const DatasetOptions& options) {
  return write_numbers(name, data.data(), data.size(), ElementType::int64, shape, options);
}

Dataset Group::write_dataset(std::string_view name, std::span<const int> data, const Shape& shape,
                             const DatasetOptions& options) {
  static_assert(sizeof(int) == 4, "int is stored as int32");
  return write_numbers(name, data.data(), data.size(), ElementType::int32, shape, options);
}

Dataset Group::write_dataset(std::string_view name, std::span<const std::int8_t> data, const Shape& shape,
                             const DatasetOptions& options) {
  return write_numbers(name, data.data(), data.size(), ElementType::int8, shape, options);
}

Dataset Group::write_dataset(std::string_view name, std::span<const std::uint8_t> data, const Shape& shape,
                             const DatasetOptions& options) {
  return write_numbers(name, data.data(), data.size(), ElementType::uint8, shape, options);
}

Dataset Group::open_dataset(std::string_view name) const {
  const std::string full_name = child_name(name);
  Handle dataset = detail::make_handle(H5Dopen2(id(), std::string(name).c_str(), H5P_DEFAULT), HandleKind::dataset,
                                       file_path_, cat("open ", detail::describe("dataset", full_name)));
  return Dataset(std::move(dataset), file_path_, full_name);
}

Group Group::create_group(std::string_view name) {
  const std::string full_name = child_name(name);
  const Handle lcpl = detail::link_creation_list(file_path_);
  const Handle gcpl = detail::make_handle(H5Pcreate(H5P_GROUP_CREATE), HandleKind::property_list, file_path_,
                                          "create property list");
  detail::track_creation_order(gcpl.get(), true, file_path_);
  Handle group = detail::make_handle(H5Gcreate2(id(), std::string(name).c_str(), lcpl.get(), gcpl.get(), H5P_DEFAULT),
                                     HandleKind::group, file_path_, cat("create ", detail::describe("group", full_name)));
  return Group(std::move(group), file_path_, full_name);
}

Group Group::open_group(std::string_view name) const {
  const std::string full_name = child_name(name);
  Handle group = detail::make_handle(H5Gopen2(id(), std::string(name).c_str(), H5P_DEFAULT), HandleKind::group,
                                     file_path_, cat("open ", detail::describe("group", full_name)));
  return Group(std::move(group), file_path_, full_name);
}

void Group::remove(std::string_view name) {
  check(H5Ldelete(id(), std::string(name).c_str(), H5P_DEFAULT), file_path_,
        cat("remove ", detail::describe("link", child_name(name))));
}

bool Group::exists(std::string_view name) const {
  // H5Lexists fails (rather than answering false) when an intermediate link is missing, so
  // walk "a/b/c" one component at a time.
  std::string prefix = name.starts_with('/') ? "/" : "";
  bool any = false;
  std::size_t begin = 0;
  while (begin <= name.size()) {
    std::size_t end = name.find('/', begin);
    if (end == std::string_view::npos) end = name.size();
    if (end > begin) {
      if (!prefix.empty() && !prefix.ends_with('/')) prefix += '/';
      prefix.append(name.substr(begin, end - begin));
      any = true;
      if (check(H5Lexists(id(), prefix.c_str(), H5P_DEFAULT), file_path_,
                cat("look up ", detail::describe("link", child_name(prefix)))) <= 0)
        return false;
    }
    begin = end + 1;
  }
  return any;
}

}  // namespace vibromap
