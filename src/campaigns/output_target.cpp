// A campaign's output file: see output_target.hpp.

#include "vibromap/campaigns/output_target.hpp"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/identity.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

constexpr std::size_t kShownDifferences = 4;  // a refused resume names the first few keys that differ

std::string gigabytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", static_cast<double>(bytes) / 1e9);
  return text;
}

// "a, b, c, d and 3 more": the first few entries, and how many more.
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < kShownDifferences; ++i) out += cat(i > 0 ? ", " : "", items[i]);
  if (items.size() > kShownDifferences) out += cat(" and ", std::to_string(items.size() - kShownDifferences), " more");
  return out;
}

}  // namespace

void check_same_run(const std::string& file, const std::vector<std::string>& differences, std::string_view scene_path) {
  if (differences.empty()) return;
  throw SceneError(cat(file, ": --resume: made by another run than ", scene_path, ": ", listed(differences),
                       "; use --overwrite to start again, or another --output"));
}

OutputTarget::OutputTarget(std::string path, const OutputPolicy& policy, OutputLocking locking)
    : path_(std::move(path)), resume_(policy.resume) {
  exists_ = check_output(path_, policy);
  if (locking == OutputLocking::lock) lock_ = std::make_unique<OutputLock>(path_);
}

void OutputTarget::check_identity(std::string_view recorded, std::string_view current, std::string_view scene_path,
                                  std::string_view also) const {
  std::vector<std::string> differences = canonical_differences(recorded, current);
  if (differences.empty() && !also.empty()) differences.emplace_back(also);
  check_same_run(path_, differences, scene_path);
}

void OutputTarget::check_space(std::uint64_t bytes, std::string_view what, std::string_view remedy) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::space_info space = fs::space(fs::absolute(path_).parent_path(), ec);
  if (!ec && bytes > space.available)
    throw IoError(cat(path_, ": ", what, " needs ", gigabytes(bytes), " GB, and its file system has ",
                      gigabytes(space.available), " GB free; ", remedy));
}

void OutputTarget::check_beside(const std::string& path, std::string_view option) const {
  check_output(path, {.option = option, .overwrite = true});
}

}  // namespace vibromap
