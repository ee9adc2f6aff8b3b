#pragma once
// Shared helpers of the scene tests: parse a scene text as if it were jobs/x.toml, and get
// the one-line SceneError of a bad one.

#include <gtest/gtest.h>

#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "vibromap/io/scene/scene.hpp"

namespace vibromap::test {

inline const std::string kFile = "jobs/x.toml";

inline Scene parse(const std::string& text, const std::vector<std::string>& sets = {}) {
  return parse_scene(text, kFile, sets);
}

// The SceneError message of a bad scene (a test failure when there is none).
inline std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse(text, sets);
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return {};
}

// a + b + ... by appending (GCC 12 warns falsely on "literal" + std::string).
inline std::string concat(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (const std::string_view p : parts) out.append(p);
  return out;
}

inline std::string source_path(const std::string& relative) { return concat({VIBROMAP_SOURCE_DIR, "/", relative}); }

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

}  // namespace vibromap::test
