// The listing part of the checked HDF5 layer (hdf5_file.hpp): the attributes of an object, their
// values as stored, the links of a group and the element type of a dataset, in a form another
// reader of the same file (h5py: postprocess/vibromap/_io/seal.py) reproduces byte for byte; and the
// removal of an attribute. The attribute checksums (attribute_seal.hpp) are built on these.

#include <hdf5.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hdf5_internal.hpp"
#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap {

using detail::check;
using detail::Handle;
using detail::HandleKind;

std::vector<std::string> Hdf5Object::attribute_names() const {
  std::vector<std::string> names;
  const auto visit = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t at = 0;
  check(H5Aiterate2(id(), H5_INDEX_NAME, H5_ITER_NATIVE, &at, visit, &names), file_path_,
        cat("list the attributes of ", detail::describe("object", name_)));
  std::sort(names.begin(), names.end());  // std::string compares bytes as unsigned, like memcmp
  return names;
}

namespace {

// A string attribute's bytes: a variable-length one up to its NUL, a fixed-length one whole
// without its trailing NULs (what numpy's bytes_ keeps).
std::string string_bytes(hid_t attr, hid_t type, std::string_view file, const std::string& what) {
  if (check(H5Tis_variable_str(type), file, "get the type of " + what) > 0) {
    const Handle mem_type = detail::vlen_string_type(file);
    char* data = nullptr;
    check(H5Aread(attr, mem_type.get(), &data), file, "read " + what);
    std::string value = data != nullptr ? data : "";
    H5free_memory(data);
    return value;
  }
  const std::size_t size = H5Tget_size(type);
  if (size == 0) check(-1, file, "get the size of " + what);
  std::string value(size, '\0');
  check(H5Aread(attr, type, value.data()), file, "read " + what);
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

}  // namespace

void Hdf5Object::remove_attribute(std::string_view name) {
  if (!has_attribute(name)) return;
  check(H5Adelete(id(), std::string(name).c_str()), file_path_, cat("remove ", detail::describe("attribute", name)));
}

AttributeValue Hdf5Object::read_attribute(std::string_view name) const {
  const std::string what = detail::describe("attribute", name);
  const Handle attr = detail::make_handle(H5Aopen(id(), std::string(name).c_str(), H5P_DEFAULT),
                                          HandleKind::attribute, file_path_, "open " + what);
  const Handle type = detail::make_handle(H5Aget_type(attr.get()), HandleKind::datatype, file_path_,
                                          "get the type of " + what);
  const Handle space = detail::make_handle(H5Aget_space(attr.get()), HandleKind::dataspace, file_path_,
                                           "get the dataspace of " + what);
  const std::size_t count = detail::element_count(space.get(), file_path_, what);
  const H5T_class_t c = detail::type_class(type.get(), file_path_, what);
  AttributeValue value;
  value.type_class = static_cast<int>(c);
  if (c == H5T_STRING && count == 1) {
    value.kind = AttributeValue::Kind::string;
    value.text = string_bytes(attr.get(), type.get(), file_path_, what);
  } else if (c == H5T_INTEGER) {
    value.kind = AttributeValue::Kind::integer;
    value.ints.resize(count);
    if (count > 0) check(H5Aread(attr.get(), H5T_NATIVE_INT64, value.ints.data()), file_path_, "read " + what);
  } else if (c == H5T_FLOAT) {
    value.kind = AttributeValue::Kind::real;
    value.reals.resize(count);
    if (count > 0) check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, value.reals.data()), file_path_, "read " + what);
  }
  return value;
}

std::string Dataset::element_type_text() const {
  const std::string what = detail::describe("dataset", name_);
  const Handle type = detail::make_handle(H5Dget_type(id()), HandleKind::datatype, file_path_, "get the type of " + what);
  const H5T_class_t c = detail::type_class(type.get(), file_path_, what);
  if (c != H5T_INTEGER && c != H5T_FLOAT) return "other";
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0) check(-1, file_path_, "get the size of " + what);
  const H5T_order_t order = H5Tget_order(type.get());
  if (order == H5T_ORDER_ERROR) check(-1, file_path_, "get the byte order of " + what);
  char kind = 'f';
  if (c == H5T_INTEGER) {
    const H5T_sign_t sign = H5Tget_sign(type.get());
    if (sign == H5T_SGN_ERROR) check(-1, file_path_, "get the sign of " + what);
    kind = sign == H5T_SGN_NONE ? 'u' : 'i';
  }
  const char byte_order = size == 1 ? '|' : (order == H5T_ORDER_BE ? '>' : '<');
  return cat(std::string(1, byte_order), std::string(1, kind), std::to_string(size));
}

bool Dataset::chunk_allocated(const Shape& offset) const {
  // The storage size looks the chunk up as a read does (H5Dget_chunk_info_by_coord does not
  // compare the whole key, and can find a chunk that reads then miss): it fails, or is 0, when
  // the chunk is not there.
  std::vector<hsize_t> at(offset.begin(), offset.end());
  hsize_t size = 0;
  if (H5Dget_chunk_storage_size(id(), at.data(), &size) < 0) {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  return size > 0;
}

std::vector<std::pair<std::string, LinkKind>> Group::links() const {
  const std::string what = detail::describe("group", name_);
  std::vector<std::pair<std::string, bool>> named;  // name, hard link
  // `auto`: H5L_info_t in HDF5 1.10, H5L_info2_t where H5Literate is H5Literate2 (1.12 on).
  const auto visit = [](hid_t, const char* name, const auto* info, void* data) -> herr_t {
    static_cast<std::vector<std::pair<std::string, bool>>*>(data)->emplace_back(name, info->type == H5L_TYPE_HARD);
    return 0;
  };
  hsize_t at = 0;
  check(H5Literate(id(), H5_INDEX_NAME, H5_ITER_NATIVE, &at, visit, &named), file_path_, "list the links of " + what);
  std::sort(named.begin(), named.end());
  std::vector<std::pair<std::string, LinkKind>> out;
  for (const auto& [name, hard] : named) {
    LinkKind kind = LinkKind::other;
    if (hard) {
      const hid_t object = H5Oopen(id(), name.c_str(), H5P_DEFAULT);
      check(object, file_path_, cat("open ", detail::describe("object", child_name(name))));
      const H5I_type_t type = H5Iget_type(object);
      H5Oclose(object);
      kind = type == H5I_GROUP ? LinkKind::group : type == H5I_DATASET ? LinkKind::dataset : LinkKind::other;
    }
    out.emplace_back(name, kind);
  }
  return out;
}

void Group::check_object_headers() const {
  const std::string what = detail::describe("group", name_);
  const auto visit = [](hid_t, const char*, const auto*, void*) -> herr_t { return 0; };
  // H5O_INFO_ALL reads each header's every chunk (H5O_INFO_HDR counts their space), which is
  // where a damaged chunk fails its checksum.
#if H5_VERSION_GE(1, 12, 0)
  check(H5Ovisit3(id(), H5_INDEX_NAME, H5_ITER_NATIVE, visit, nullptr, H5O_INFO_ALL), file_path_,
        "read the object headers under " + what);
#else
  check(H5Ovisit2(id(), H5_INDEX_NAME, H5_ITER_NATIVE, visit, nullptr, H5O_INFO_ALL), file_path_,
        "read the object headers under " + what);
#endif
}

}  // namespace vibromap
