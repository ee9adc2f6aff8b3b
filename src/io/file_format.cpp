// The refusal of a file of another format version (file_format.hpp).

#include "vibromap/io/file_format.hpp"

#include "vibromap/core/text.hpp"

namespace vibromap {

std::string version_refusal(std::string_view path, const FileFormat& format, std::int64_t found) {
  const bool vowel = std::string_view("aeiou").find(format.kind.front()) != std::string_view::npos;
  return cat(path, vowel ? ": an " : ": a ", format.kind, " of format version ", std::to_string(found), "; this vibromap reads version ",
             std::to_string(format.version), " only: make the file again with this vibromap");
}

void check_version(std::string_view path, const FileFormat& format, std::int64_t found) {
  if (found != format.version) throw FileVersionError(version_refusal(path, format, found));
}

}  // namespace vibromap
