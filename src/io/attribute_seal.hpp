#pragma once
// Internal to io: the attribute checksum of a vibromap HDF5 file ("the seal").
//
// Chunks carry HDF5's Fletcher32 checksum, but attributes do not: a variable-length string
// attribute (the scene, the identity, the title, a unit) lives in HDF5's global heap, which has
// no checksum, so one flipped byte there could empty or change it unnoticed. The seal closes
// that gap: the root attribute `attribute_checksum` holds "crc32 XXXXXXXX" (8 lowercase hex
// digits), the CRC-32 (zlib's) of the canonical record of the file's metadata below, optionally
// followed by "; not covered: NAME NAME..." (root attributes a writer updates in place later and
// that readers never trust: a map's cells_done, complete and ranks, rewritten when a run ends;
// a root group of that name is left out too: a census map's /families, rewritten by each family
// pass).
//
// The canonical record, built identically by attribute_record() here and by
// postprocess/vibromap/_io/seal.py (attribute_record), is a byte string: for each object, the root
// group "/" first, then depth first through the links of each group, sorted by name:
//   - a dataset's layout: field(path) field("") "l" field("<dtype> <shape> <scales>"), where dtype
//     is numpy's spelling ("<f8", "|i1"), shape "3x4" ("scalar" for none) and scales the paths
//     of the dimension scales attached to each dimension, ',' within one, ';' between dimensions;
//   - every attribute, sorted by name, but DIMENSION_LIST and REFERENCE_LIST (HDF5's object
//     references, which the layout's scales stand for), the seal itself and the uncovered ones:
//     field(path) field(name) KIND field(value), KIND "s" (a string: its bytes), "i" (integers:
//     the decimal values joined by ','), "f" (floats: each one's IEEE 754 bits as 16 lowercase
//     hex digits, joined by ',') or "x" (anything else: the HDF5 type class number);
//   - a link that is neither a group nor a dataset: field(path) field("") "x" field("link");
// where field(b) is the decimal byte length of b, ':', then b.
//
// Every file carries a seal: one without it is damaged (a file made before vibromap sealed its
// files is also of an older format version, and refused for that first: file_format.hpp).

#include <string>
#include <string_view>
#include <vector>

#include "vibromap/io/file_format.hpp"
#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

inline constexpr std::string_view kSealAttribute = "attribute_checksum";

// The canonical record of `file`'s metadata (see above), without the root attributes `uncovered`.
std::string attribute_record(const Hdf5File& file, const std::vector<std::string>& uncovered);

// Writes the root attribute `version` (format.version), then the seal over every attribute
// written so far: call it after the last of them. Root attributes in `uncovered` may change
// later without breaking it. Throws IoError.
void seal_attributes(Hdf5File& file, const FileFormat& format, const std::vector<std::string>& uncovered = {});

// What every reader of a vibromap HDF5 file checks before it reads any value, in this order:
// 1. the global heaps (below): one that HDF5 would read for ever is damage;
// 2. the format version: FileVersionError unless the root attribute `version` is
//    format.version (a file without it but with `vibromap_version` is version 0); a file with
//    neither is IoError "<path>: not a vibromap <kind> (no root attribute 'version')";
// 3. the seal: IoError "<path>: damaged: its attributes fail their checksum (...); make it
//    again with --overwrite" (or: it has none, it is unreadable) when the attributes are damaged.
void verify_file(const Hdf5File& file, const FileFormat& format);

}  // namespace vibromap::detail
