#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/output_file.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <type_traits>

#include "hdf5_internal.hpp"
#include "vibromap/core/text.hpp"

// The public header spells hid_t as detail::Hid so that it need not include <hdf5.h>.
static_assert(std::is_same_v<hid_t, vibromap::detail::Hid>, "HDF5 >= 1.10 with 64-bit hid_t expected");

namespace vibromap {
namespace detail {
namespace {

// HDF5 prints its whole error stack to stderr on every failure unless told not to; we report
// errors as one IoError line instead. Called before the first file is created or opened.
//
// Also: no HDF5 clean-up at exit. Every file is closed by its owner before the process ends;
// HDF5's own atexit pass only closes what a failed close left half-closed (a write that failed
// with EFBIG or ENOSPC), and crashed doing so (a segfault in H5F__close_cb). H5dont_atexit must
// come before the library's first real call, so this runs before the first file is made or
// opened.
void silence_hdf5_error_printing() {
  static const bool done = [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

// The description of the innermost error on HDF5's default stack (where the failure was
// first detected), shortened to the system's message when HDF5 quotes one.
std::string innermost_hdf5_reason() {
  std::string reason;
  const auto visit = [](unsigned n, const H5E_error2_t* err, void* data) -> herr_t {
    if (n == 0 && err->desc != nullptr) *static_cast<std::string*>(data) = err->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &reason);
  H5Eclear2(H5E_DEFAULT);
  // "unable to open file: name = '...', errno = 2, error message = 'No such file or directory', ..."
  const std::string_view key = "error message = '";
  if (const auto at = reason.find(key); at != std::string::npos) {
    const auto begin = at + key.size();
    const auto end = reason.find('\'', begin);
    if (end != std::string::npos) reason = reason.substr(begin, end - begin);
  }
  for (char& c : reason)
    if (c == '\n' || c == '\r') c = ' ';
  return reason;
}

}  // namespace

// "attribute 'units'", "dataset '/x1'": how messages name an object.
std::string describe(std::string_view kind, std::string_view name) { return cat(kind, " '", name, "'"); }

Handle make_handle(Hid id, HandleKind kind, std::string_view file, std::string_view operation) {
  return Handle(check(id, file, operation), kind);
}

// A variable-length UTF-8 string type (what h5py writes for str and reads back as str).
Handle vlen_string_type(std::string_view file) {
  Handle type = make_handle(H5Tcopy(H5T_C_S1), HandleKind::datatype, file, "copy string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), file, "make string type variable-length");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), file, "set string type to UTF-8");
  return type;
}

// Link creation that makes missing intermediate groups, so "a/b/c" works in one call.
Handle link_creation_list(std::string_view file) {
  Handle lcpl = make_handle(H5Pcreate(H5P_LINK_CREATE), HandleKind::property_list, file, "create property list");
  check(H5Pset_create_intermediate_group(lcpl.get(), 1), file, "set intermediate group creation");
  return lcpl;
}

// netCDF-4 files track and index the creation order of links and attributes (netCDF-C sets
// this on every file, group and variable it creates): netCDF readers then list variables and
// attributes in the order written. `plist` is a file, group or dataset creation property
// list; links are only tracked on the first two.
void track_creation_order(Hid plist, bool links, std::string_view file) {
  const unsigned flags = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
  if (links) check(H5Pset_link_creation_order(plist, flags), file, "set link creation order tracking");
  check(H5Pset_attr_creation_order(plist, flags), file, "set attribute creation order tracking");
}

// (file type, memory type) of an element type.
std::pair<Hid, Hid> element_types(ElementType element) {
  switch (element) {
    case ElementType::int64: return {H5T_STD_I64LE, H5T_NATIVE_INT64};
    case ElementType::int32: return {H5T_STD_I32LE, H5T_NATIVE_INT32};
    case ElementType::int8: return {H5T_STD_I8LE, H5T_NATIVE_INT8};
    case ElementType::uint8: return {H5T_STD_U8LE, H5T_NATIVE_UINT8};
    case ElementType::float64: break;
  }
  return {H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE};
}

// Number of elements of an attribute or dataset's dataspace.
std::size_t element_count(Hid space, std::string_view file, std::string_view what) {
  return static_cast<std::size_t>(check(H5Sget_simple_extent_npoints(space), file, cat("get the size of ", what)));
}

H5T_class_t type_class(Hid type, std::string_view file, std::string_view what) {
  const H5T_class_t c = H5Tget_class(type);
  if (c == H5T_NO_CLASS) check(-1, file, cat("get the type of ", what));
  return c;
}

namespace {

// Opens attribute `name` on `loc` and checks that it holds one element.
Handle open_scalar_attribute(Hid loc, std::string_view name, std::string_view file) {
  const std::string what = detail::describe("attribute", name);
  Handle attr = make_handle(H5Aopen(loc, std::string(name).c_str(), H5P_DEFAULT), HandleKind::attribute, file,
                            "open " + what);
  Handle space = make_handle(H5Aget_space(attr.get()), HandleKind::dataspace, file, "get the dataspace of " + what);
  if (element_count(space.get(), file, what) != 1) fail(file, what + " is not a scalar");
  return attr;
}

// Reads a numeric scalar attribute converted to `mem_type`; integers may not be read from floats.
void read_numeric_attribute(Hid loc, std::string_view name, std::string_view file, hid_t mem_type, void* out,
                            bool integer) {
  const std::string what = detail::describe("attribute", name);
  Handle attr = open_scalar_attribute(loc, name, file);
  Handle type = make_handle(H5Aget_type(attr.get()), HandleKind::datatype, file, "get the type of " + what);
  const H5T_class_t c = type_class(type.get(), file, what);
  if (c != H5T_INTEGER && (integer || c != H5T_FLOAT))
    fail(file, what + (integer ? " is not an integer" : " is not a number"));
  check(H5Aread(attr.get(), mem_type, out), file, "read " + what);
}

}  // namespace

// Creates (or replaces) an attribute of file type `file_type` and writes `value`: a scalar
// when `count` is 0, else a 1-D array of `count` elements.
void write_attribute(Hid loc, std::string_view name, std::string_view file, hid_t file_type, hid_t mem_type,
                     const void* value, std::size_t count) {
  const std::string attr_name(name);
  const std::string what = detail::describe("attribute", name);
  if (check(H5Aexists(loc, attr_name.c_str()), file, "look up " + what) > 0)
    check(H5Adelete(loc, attr_name.c_str()), file, "replace " + what);
  const hsize_t dims[1] = {count};
  Handle space = make_handle(count == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr),
                             HandleKind::dataspace, file, "create dataspace for " + what);
  Handle attr = make_handle(H5Acreate2(loc, attr_name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                            HandleKind::attribute, file, "create " + what);
  check(H5Awrite(attr.get(), mem_type, value), file, "write " + what);
}


std::int64_t check(std::int64_t ret, std::string_view file, std::string_view operation) {
  if (ret >= 0) return ret;
  const std::string reason = innermost_hdf5_reason();
  std::string message = cat(file, ": cannot ", operation);
  if (!reason.empty()) message += " (" + reason + ")";
  throw IoError(message);
}

void fail(std::string_view file, std::string_view message) {
  throw IoError(cat(file, ": ", message));
}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    kind_ = other.kind_;
    other.id_ = -1;
  }
  return *this;
}

void Handle::reset() noexcept {
  if (id_ < 0) return;
  herr_t rc = 0;
  switch (kind_) {
    case HandleKind::file: rc = H5Fclose(id_); break;
    case HandleKind::group: rc = H5Gclose(id_); break;
    case HandleKind::dataset: rc = H5Dclose(id_); break;
    case HandleKind::dataspace: rc = H5Sclose(id_); break;
    case HandleKind::datatype: rc = H5Tclose(id_); break;
    case HandleKind::attribute: rc = H5Aclose(id_); break;
    case HandleKind::property_list: rc = H5Pclose(id_); break;
  }
  if (rc < 0) H5Eclear2(H5E_DEFAULT);  // nothing to report from a destructor; keep the stack clean
  id_ = -1;
}

}  // namespace detail

using detail::check;
using detail::fail;
using detail::Handle;
using detail::HandleKind;

// ---- Hdf5Object: attributes -------------------------------------------------------------

std::string Hdf5Object::child_name(std::string_view child) const {
  if (!child.empty() && child.front() == '/') return std::string(child);
  return (name_ == "/" ? name_ : name_ + "/") + std::string(child);
}

void Hdf5Object::set_attribute(std::string_view name, std::string_view value) {
  const std::string text(value);  // NUL-terminated copy: HDF5 stores C strings
  const char* data = text.c_str();
  const Handle type = detail::vlen_string_type(file_path_);
  detail::write_attribute(id(), name, file_path_, type.get(), type.get(), &data);
}

void Hdf5Object::set_attribute(std::string_view name, double value) {
  detail::write_attribute(id(), name, file_path_, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5Object::set_int_attribute(std::string_view name, std::int64_t value) {
  detail::write_attribute(id(), name, file_path_, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void Hdf5Object::set_attribute(std::string_view name, std::span<const std::int8_t> values) {
  set_array_attribute(name, values.data(), values.size(), true);
}

void Hdf5Object::set_attribute(std::string_view name, std::span<const double> values) {
  set_array_attribute(name, values.data(), values.size(), false);
}

void Hdf5Object::set_array_attribute(std::string_view name, const void* values, std::size_t count, bool as_int8) {
  if (count == 0) fail(file_path_, cat("cannot write ", detail::describe("attribute", name), ": empty array"));
  detail::write_attribute(id(), name, file_path_, as_int8 ? H5T_STD_I8LE : H5T_IEEE_F64LE,
                          as_int8 ? H5T_NATIVE_INT8 : H5T_NATIVE_DOUBLE, values, count);
}

bool Hdf5Object::has_attribute(std::string_view name) const {
  return check(H5Aexists(id(), std::string(name).c_str()), file_path_, cat("look up ", detail::describe("attribute", name))) > 0;
}

double Hdf5Object::read_double_attribute(std::string_view name) const {
  double value = 0.0;
  detail::read_numeric_attribute(id(), name, file_path_, H5T_NATIVE_DOUBLE, &value, false);
  return value;
}

std::int64_t Hdf5Object::read_int_attribute(std::string_view name) const {
  std::int64_t value = 0;
  detail::read_numeric_attribute(id(), name, file_path_, H5T_NATIVE_INT64, &value, true);
  return value;
}

std::size_t Hdf5Object::attribute_size(std::string_view name) const {
  const std::string what = detail::describe("attribute", name);
  const Handle attr = detail::make_handle(H5Aopen(id(), std::string(name).c_str(), H5P_DEFAULT),
                                          HandleKind::attribute, file_path_, "open " + what);
  const Handle space = detail::make_handle(H5Aget_space(attr.get()), HandleKind::dataspace, file_path_,
                                           "get the dataspace of " + what);
  return detail::element_count(space.get(), file_path_, what);
}

void Hdf5Object::read_array_attribute(std::string_view name, void* out, std::size_t count, bool as_double) const {
  const std::string what = detail::describe("attribute", name);
  const Handle attr = detail::make_handle(H5Aopen(id(), std::string(name).c_str(), H5P_DEFAULT),
                                          HandleKind::attribute, file_path_, "open " + what);
  const Handle type = detail::make_handle(H5Aget_type(attr.get()), HandleKind::datatype, file_path_,
                                          "get the type of " + what);
  const H5T_class_t c = detail::type_class(type.get(), file_path_, what);
  if (c != H5T_INTEGER && (!as_double || c != H5T_FLOAT))
    fail(file_path_, what + (as_double ? " is not a number" : " is not an integer"));
  if (count == 0) return;
  check(H5Aread(attr.get(), as_double ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, out), file_path_, "read " + what);
}

std::vector<std::int64_t> Hdf5Object::read_int_array_attribute(std::string_view name) const {
  std::vector<std::int64_t> values(attribute_size(name));
  read_array_attribute(name, values.data(), values.size(), false);
  return values;
}

std::vector<double> Hdf5Object::read_double_array_attribute(std::string_view name) const {
  std::vector<double> values(attribute_size(name));
  read_array_attribute(name, values.data(), values.size(), true);
  return values;
}

std::string Hdf5Object::read_string_attribute(std::string_view name) const {
  const std::string what = detail::describe("attribute", name);
  const Handle attr = detail::open_scalar_attribute(id(), name, file_path_);
  const Handle type = detail::make_handle(H5Aget_type(attr.get()), HandleKind::datatype, file_path_,
                                          "get the type of " + what);
  if (detail::type_class(type.get(), file_path_, what) != H5T_STRING) fail(file_path_, what + " is not a string");
  if (check(H5Tis_variable_str(type.get()), file_path_, "get the type of " + what) > 0) {
    const Handle mem_type = detail::vlen_string_type(file_path_);
    char* data = nullptr;
    check(H5Aread(attr.get(), mem_type.get(), &data), file_path_, "read " + what);
    std::string value = data != nullptr ? data : "";
    H5free_memory(data);
    return value;
  }
  // Fixed-length string (as written by other tools): read into a NUL-terminated buffer.
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0) check(-1, file_path_, "get the size of " + what);
  const Handle mem_type = detail::make_handle(H5Tcopy(H5T_C_S1), HandleKind::datatype, file_path_, "copy string type");
  check(H5Tset_size(mem_type.get(), size + 1), file_path_, "set string size");
  check(H5Tset_strpad(mem_type.get(), H5T_STR_NULLTERM), file_path_, "set string padding");
  std::vector<char> buffer(size + 1, '\0');
  check(H5Aread(attr.get(), mem_type.get(), buffer.data()), file_path_, "read " + what);
  return std::string(buffer.data());
}

// ---- Hdf5File ---------------------------------------------------------------------------

namespace {

Handle file_access_list(const std::string& path, const FileOptions& options) {
  Handle fapl = detail::make_handle(H5Pcreate(H5P_FILE_ACCESS), HandleKind::property_list, path, "create property list");
  check(H5Pset_file_locking(fapl.get(), options.locking, true), path, "set file locking");
  // 521 slots (HDF5's default count), w0 = 1: chunks read or written whole leave the cache first.
  check(H5Pset_cache(fapl.get(), 0, 521, options.chunk_cache_bytes, 1.0), path, "set the chunk cache");
  if (options.format_1_8)
    check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), path, "set the file format");
  return fapl;
}

Handle open_file(const std::string& path, FileMode mode, const FileOptions& options) {
  detail::silence_hdf5_error_printing();
  const Handle fapl = file_access_list(path, options);
  switch (mode) {
    case FileMode::truncate: {
      const Handle fcpl = detail::make_handle(H5Pcreate(H5P_FILE_CREATE), HandleKind::property_list, path,
                                              "create property list");
      detail::track_creation_order(fcpl.get(), true, path);
      return detail::make_handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), HandleKind::file,
                                 path, "create file");
    }
    case FileMode::read_write:
      return detail::make_handle(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), HandleKind::file, path,
                                 "open file for writing");
    case FileMode::read_only:
      break;
  }
  return detail::make_handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), HandleKind::file, path,
                             "open file for reading");
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, FileMode mode, const FileOptions& options)
    : Group(open_file(path, mode, options), path, "/") {}

void Hdf5File::flush() { check(H5Fflush(id(), H5F_SCOPE_LOCAL), file_path_, "flush file"); }

int Hdf5File::descriptor() const {
  void* handle = nullptr;
  check(H5Fget_vfd_handle(id(), H5P_DEFAULT, &handle), file_path_, "get the file's descriptor");
  if (handle == nullptr) fail(file_path_, "the file has no descriptor (not a POSIX file driver)");
  return *static_cast<int*>(handle);
}

void Hdf5File::sync() {
  flush();
  if (::fsync(descriptor()) != 0) fail(file_path_, cat("cannot sync the file to disk (", std::strerror(errno), ")"));
}

void Hdf5File::start_writeback() {
  // Asks the kernel to start writing the file's dirty pages now, without waiting for them, so
  // that the next sync() finds little left to do (RocksDB's bytes_per_sync does the same).
  ::sync_file_range(descriptor(), 0, 0, SYNC_FILE_RANGE_WRITE);
}

void Hdf5File::close() {
  if (!handle_.valid()) return;
  check(H5Fclose(handle_.release()), file_path_, "close file");
}

// ---- atomic writing ---------------------------------------------------------------------

void write_hdf5_atomically(const std::string& path, const std::function<void(Hdf5File&)>& fill) {
  NewFile out(path);
  out.close_descriptor();
  {
    Hdf5File file(out.path(), FileMode::truncate);
    out.check_same(file.descriptor());
    fill(file);
    file.close();
  }
  out.commit();
}

}  // namespace vibromap

