#pragma once
// Internal to the HDF5 layer (hdf5_file.cpp, hdf5_dataset.cpp): the helpers both halves use.

#include <hdf5.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>

#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

// "attribute 'units'", "dataset '/x1'": how messages name an object.
std::string describe(std::string_view kind, std::string_view name);
// A handle of `kind` for `id`, or IoError "<file>: cannot <operation> (...)" when id < 0.
Handle make_handle(Hid id, HandleKind kind, std::string_view file, std::string_view operation);
// A variable-length UTF-8 string type (what h5py writes for str and reads back as str).
Handle vlen_string_type(std::string_view file);
// Link creation that makes missing intermediate groups, so "a/b/c" works in one call.
Handle link_creation_list(std::string_view file);
// netCDF-4's creation-order tracking on a file, group (links too) or dataset creation list.
void track_creation_order(Hid plist, bool links, std::string_view file);
// (file type, memory type) of an element type.
std::pair<Hid, Hid> element_types(ElementType element);
// Number of elements of an attribute or dataset's dataspace.
std::size_t element_count(Hid space, std::string_view file, std::string_view what);
H5T_class_t type_class(Hid type, std::string_view file, std::string_view what);
// Creates (or replaces) an attribute of file type `file_type` and writes `value`: a scalar when
// `count` is 0, else a 1-D array of `count` elements.
void write_attribute(Hid loc, std::string_view name, std::string_view file, hid_t file_type, hid_t mem_type,
                     const void* value, std::size_t count = 0);

}  // namespace vibromap::detail
