#pragma once
// The format version of every kind of file vibromap writes, declared here and nowhere else in
// the C++ (postprocess/vibromap/_io/h5io.py's FORMAT_VERSIONS holds the same numbers for the Python
// readers; docs/file-formats.md lists them).
//
// An HDF5 file carries its kind's version as the integer root attribute `version`, the last one
// written before the attribute checksum (attribute_seal.hpp); a file without it is version 0
// (made before vibromap versioned its files). The optimisation journal carries its version in its
// header (journal.hpp). vibromap reads exactly the version it writes: a file of any other
// version, older or newer, is refused before any of its values is read, with FileVersionError,
// one line naming the file and both versions (exit 2). There is no reader of an older layout:
// a change of a kind's layout raises its version here (and in the Python table), and the files
// made before are made again.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vibromap {

struct FileFormat {
  std::string_view kind;  // how messages name the file: "regime map"
  std::int64_t version;   // the version this vibromap writes and reads
};

// Map 2: census maps carry /basin_entropy, /attractor_strobe and the families.
inline constexpr FileFormat kMapFormat{"regime map", 2};  // sweep (uniform, census, adaptive), optimise's seeding map
inline constexpr FileFormat kBasinsFormat{"basins file", 1};
inline constexpr FileFormat kOptimiseFormat{"optimisation file", 1};
inline constexpr FileFormat kTrajectoryFormat{"trajectory file", 1};
inline constexpr FileFormat kBranchFormat{"branch file", 1};
inline constexpr FileFormat kCurveFormat{"curve file", 1};
inline constexpr FileFormat kOrbitDiagramFormat{"orbit-diagram file", 1};
// 2: census attractor records carry the transient flag; 3: and budget_fraction.
inline constexpr FileFormat kJournalFormat{"optimisation journal", 3};

// The root attribute that holds an HDF5 file's version.
inline constexpr std::string_view kVersionAttribute = "version";

// A file of another format version than this vibromap's. what() is one line:
// "<path>: a regime map of format version 0; this vibromap reads version 1 only: make the file
// again with this vibromap". The command line exits 2 on it.
class FileVersionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// FileVersionError's line for a file of kind `format` found at version `found`.
std::string version_refusal(std::string_view path, const FileFormat& format, std::int64_t found);

// Throws FileVersionError unless `found` is the version this vibromap reads.
void check_version(std::string_view path, const FileFormat& format, std::int64_t found);

}  // namespace vibromap
