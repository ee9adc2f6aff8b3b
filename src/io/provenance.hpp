#pragma once
// Internal to io: the root attributes every vibromap result file of a stepped key carries
// (title, CF conventions, version, the scene text and the key), in one place.

#include <string>

#include "vibromap/io/hdf5_file.hpp"

namespace vibromap::detail {

inline void set_provenance(Hdf5File& file, const std::string& title, const std::string& scene_text,
                           const std::string& key) {
  file.set_attribute("title", title);
  file.set_attribute("Conventions", "CF-1.8");
  file.set_attribute("vibromap_version", VIBROMAP_VERSION);
  file.set_attribute("scene", scene_text);
  file.set_attribute("key", key);
}

}  // namespace vibromap::detail
