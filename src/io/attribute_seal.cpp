// The attribute checksum of vibromap's HDF5 files (attribute_seal.hpp documents the record).

#include "attribute_seal.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <optional>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vibromap/core/text.hpp"
#include "vibromap/io/journal.hpp"

namespace vibromap::detail {
namespace {

constexpr std::string_view kCrcPrefix = "crc32 ";
constexpr std::string_view kUncoveredPrefix = "; not covered: ";

// field(b): its byte length in decimal, ':', then b.
void append_field(std::string& out, std::string_view bytes) {
  out.append(std::to_string(bytes.size())).append(":").append(bytes);
}

void append_record(std::string& out, std::string_view path, std::string_view name, char kind, std::string_view value) {
  append_field(out, path);
  append_field(out, name);
  out.push_back(kind);
  append_field(out, value);
}

std::string hex(std::uint64_t value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%0*llx", digits, static_cast<unsigned long long>(value));
  return buffer;
}

// An attribute's value in the record: its kind letter and its text.
std::pair<char, std::string> value_text(const AttributeValue& v) {
  std::string text;
  switch (v.kind) {
    case AttributeValue::Kind::string: return {'s', v.text};
    case AttributeValue::Kind::integer:
      for (const std::int64_t i : v.ints) text.append(text.empty() ? "" : ",").append(std::to_string(i));
      return {'i', text};
    case AttributeValue::Kind::real:
      for (const double x : v.reals) text.append(text.empty() ? "" : ",").append(hex(std::bit_cast<std::uint64_t>(x), 16));
      return {'f', text};
    case AttributeValue::Kind::other: break;
  }
  return {'x', std::to_string(v.type_class)};
}

// "<f8 3x4 /E1;/E2": a dataset's element type, shape and attached dimension scales.
std::string layout_text(const Dataset& d) {
  const Shape shape = d.shape();
  std::string dims, scales;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    dims.append(i ? "x" : "").append(std::to_string(shape[i]));
    std::string attached;
    for (const std::string& s : d.attached_scales(i)) attached.append(attached.empty() ? "" : ",").append(s);
    scales.append(i ? ";" : "").append(attached);
  }
  return cat(d.element_type_text(), " ", dims.empty() ? std::string("scalar") : dims, " ", scales);
}

void append_attributes(std::string& out, const Hdf5Object& object, const std::vector<std::string>& skipped) {
  for (const std::string& name : object.attribute_names()) {
    if (name == "DIMENSION_LIST" || name == "REFERENCE_LIST") continue;
    if (std::find(skipped.begin(), skipped.end(), name) != skipped.end()) continue;
    const auto [kind, text] = value_text(object.read_attribute(name));
    append_record(out, object.name(), name, kind, text);
  }
}

void append_group(std::string& out, const Group& group, const std::vector<std::string>& skipped = {}) {
  for (const auto& [name, kind] : group.links()) {
    if (std::find(skipped.begin(), skipped.end(), name) != skipped.end()) continue;
    const std::string path = group.name() == "/" ? "/" + name : group.name() + "/" + name;
    if (kind == LinkKind::dataset) {
      const Dataset d = group.open_dataset(name);
      append_record(out, path, "", 'l', layout_text(d));
      append_attributes(out, d, {});
    } else if (kind == LinkKind::group) {
      const Group g = group.open_group(name);
      append_attributes(out, g, {});
      append_group(out, g);
    } else {
      append_record(out, path, "", 'x', "link");
    }
  }
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out.append(out.empty() ? "" : " ").append(n);
  return out;
}

// `text` for a one-line message: control and non-ASCII bytes as \xNN, cut to 60 characters.
std::string printable(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, 60)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out.push_back(c);
    } else {
      out.append("\\x").append(hex(u, 2));
    }
  }
  if (text.size() > 60) out.append("...");
  return out;
}

[[noreturn]] void damaged(const Hdf5File& file, std::string_view why) {
  fail(file.path(), cat("damaged: ", why, "; make it again with --overwrite"));
}

// The seal's value parsed: the CRC as 8 hex digits and the uncovered root attributes; false
// when it is not of the form "crc32 XXXXXXXX[; not covered: NAME...]".
bool parse_seal(std::string_view text, std::string& crc, std::vector<std::string>& uncovered) {
  if (!text.starts_with(kCrcPrefix) || text.size() < kCrcPrefix.size() + 8) return false;
  crc = std::string(text.substr(kCrcPrefix.size(), 8));
  if (!std::all_of(crc.begin(), crc.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); }))
    return false;
  std::string_view rest = text.substr(kCrcPrefix.size() + 8);
  if (rest.empty()) return true;
  if (!rest.starts_with(kUncoveredPrefix)) return false;
  rest.remove_prefix(kUncoveredPrefix.size());
  while (!rest.empty()) {
    const std::size_t end = std::min(rest.find(' '), rest.size());
    const std::string_view name = rest.substr(0, end);
    if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) { return c == '_' || (c >= 'a' && c <= 'z'); }))
      return false;
    uncovered.emplace_back(name);
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  return !uncovered.empty();
}

// ---- Global heaps that HDF5 would read for ever -------------------------------------------
// A string attribute's bytes live in a global heap collection ("GCOL", version 1, then its size
// in 8 bytes): objects one after another, each a 16-byte header (index 2 bytes, references 2,
// reserved 4, size 8) and its data padded to 8 bytes; index 0 is the free space, which has no
// header padding. HDF5 1.10 walks a collection object by object when it first reads from it, and
// a free-space object of size 0 never advances the walk: one flipped bit in a size can make the
// library loop for ever. The walk is repeated here, on the bytes, before any attribute is read.

constexpr char kHeapSignature[] = {'G', 'C', 'O', 'L', 1, 0, 0, 0};
constexpr std::uint64_t kScanWhole = std::uint64_t{1} << 30;  // files up to this are scanned whole,
constexpr std::uint64_t kScanEnds = std::uint64_t{256} << 20;  // larger ones at both ends (their heaps)

std::uint64_t little_endian(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// Where the walk of the collection at `at` would stop advancing, or 0.
std::uint64_t stuck_object(int fd, std::uint64_t at, std::uint64_t file_size) {
  unsigned char head[16];
  if (::pread(fd, head, sizeof head, static_cast<off_t>(at)) != static_cast<ssize_t>(sizeof head)) return 0;
  const std::uint64_t size = std::min(little_endian(head + 8, 8), file_size - at);
  std::vector<unsigned char> heap(static_cast<std::size_t>(size));
  if (size < 16 || ::pread(fd, heap.data(), heap.size(), static_cast<off_t>(at)) != static_cast<ssize_t>(size)) return 0;
  for (std::uint64_t p = 16; p + 16 <= size;) {
    const std::uint64_t index = little_endian(&heap[p], 2), object = little_endian(&heap[p + 8], 8);
    const std::uint64_t need = index > 0 ? 16 + ((object + 7) / 8) * 8 : object;
    if (need == 0) return at + p;
    if (need > size - p) break;
    p += need;
  }
  return 0;
}

// Calls visit(offset) for each collection signature in [from, to) of the file.
void find_heaps(int fd, std::uint64_t from, std::uint64_t to, const std::function<void(std::uint64_t)>& visit) {
  constexpr std::size_t kBlock = std::size_t{4} << 20;
  std::vector<char> block(kBlock + sizeof kHeapSignature);
  for (std::uint64_t at = from; at < to; at += kBlock) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(kBlock + sizeof kHeapSignature - 1, to - at));
    const ssize_t got = ::pread(fd, block.data(), want, static_cast<off_t>(at));
    if (got <= 0) return;
    const char* end = block.data() + got;
    for (const char* p = block.data(); (p = std::search(p, end, std::begin(kHeapSignature), std::end(kHeapSignature))) != end; ++p)
      visit(at + static_cast<std::uint64_t>(p - block.data()));
  }
}

// Empty, or why HDF5 would loop for ever reading the file's attributes.
std::string endless_global_heap(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};  // HDF5 opened it: a failure here says nothing about its heaps
  struct stat st {};
  std::uint64_t stuck = 0;
  if (::fstat(fd, &st) == 0) {
    const auto size = static_cast<std::uint64_t>(st.st_size);
    const auto visit = [&](std::uint64_t at) {
      if (stuck == 0) stuck = stuck_object(fd, at, size);
    };
    if (size <= kScanWhole) {
      find_heaps(fd, 0, size, visit);
    } else {
      find_heaps(fd, 0, kScanEnds, visit);
      find_heaps(fd, size - kScanEnds, size, visit);
    }
  }
  ::close(fd);
  if (stuck == 0) return {};
  return cat("a global heap (HDF5's store of string attributes) has a free-space object of size 0 at byte ",
             std::to_string(stuck), ", which the HDF5 library would read for ever");
}

// `read()`, with what HDF5 throws while reading attributes ("<path>: cannot read attribute 'x'
// (reason)") reported as damage.
template <class Read>
auto read_attributes(const Hdf5File& file, Read&& read) {
  try {
    return read();
  } catch (const IoError& e) {
    const std::string_view what = e.what();
    if (what.starts_with(cat(file.path(), ": damaged: "))) throw;
    const std::string prefix = cat(file.path(), ": ");
    damaged(file, cat("its attributes cannot be read (", what.starts_with(prefix) ? what.substr(prefix.size()) : what, ")"));
  }
}

// The file's format version: its root attribute `version`, 0 when it has only vibromap_version
// (made before files were versioned).
std::int64_t stored_version(const Hdf5File& file, const FileFormat& format) {
  const auto version = read_attributes(file, [&]() -> std::optional<std::int64_t> {
    if (!file.has_attribute(kVersionAttribute)) {
      if (file.has_attribute("vibromap_version")) return 0;
      return std::nullopt;
    }
    const AttributeValue v = file.read_attribute(kVersionAttribute);
    if (v.kind != AttributeValue::Kind::integer || v.ints.size() != 1)
      damaged(file, cat("its attribute '", kVersionAttribute, "' is not one integer"));
    return v.ints.front();
  });
  if (!version) fail(file.path(), cat("not a vibromap ", format.kind, " (no root attribute '", kVersionAttribute, "')"));
  return *version;
}

void check_seal(const Hdf5File& file) {
  read_attributes(file, [&] {
    if (!file.has_attribute(kSealAttribute)) damaged(file, cat("it has no attribute '", kSealAttribute, "'"));
    const AttributeValue seal = file.read_attribute(kSealAttribute);
    std::string stored;
    std::vector<std::string> uncovered;
    if (seal.kind != AttributeValue::Kind::string || !parse_seal(seal.text, stored, uncovered))
      damaged(file, cat("its attribute '", kSealAttribute, "' is not 'crc32 XXXXXXXX' ('", printable(seal.text), "')"));
    const std::string record = attribute_record(file, uncovered);
    const std::string computed = hex(crc32(record.data(), record.size()), 8);
    if (computed != stored)
      damaged(file, cat("its attributes fail their checksum (", kSealAttribute, " says crc32 ", stored,
                        ", the attributes give ", computed, ")"));
  });
}

// Every object's header reads whole: the data and attributes can read while a header chunk
// they do not use fails its checksum, and h5py's walk of the file (visititems) then fails.
void check_object_headers(const Hdf5File& file) {
  try {
    file.check_object_headers();
  } catch (const IoError& e) {
    const std::string_view what = e.what();
    const std::string prefix = cat(file.path(), ": ");
    damaged(file, cat("an object's header cannot be read (", what.starts_with(prefix) ? what.substr(prefix.size()) : what,
                      ")"));
  }
}

}  // namespace

std::string attribute_record(const Hdf5File& file, const std::vector<std::string>& uncovered) {
  std::vector<std::string> skipped = uncovered;
  skipped.emplace_back(kSealAttribute);
  std::string out;
  append_attributes(out, file, skipped);
  append_group(out, file, uncovered);
  return out;
}

void seal_attributes(Hdf5File& file, const FileFormat& format, const std::vector<std::string>& uncovered) {
  file.set_attribute(kVersionAttribute, format.version);
  const std::string record = attribute_record(file, uncovered);
  std::string value = cat(kCrcPrefix, hex(crc32(record.data(), record.size()), 8));
  if (!uncovered.empty()) value += cat(kUncoveredPrefix, joined(uncovered));
  file.set_attribute(kSealAttribute, value);
}

void verify_file(const Hdf5File& file, const FileFormat& format) {
  if (const std::string why = endless_global_heap(file.path()); !why.empty()) damaged(file, why);
  check_object_headers(file);
  check_version(file.path(), format, stored_version(file, format));
  check_seal(file);
}

}  // namespace vibromap::detail
