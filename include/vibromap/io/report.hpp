#pragma once
// The reporter: the small pieces every command's stdout is made of, tables for people and JSON
// for scripts (io/json_writer.hpp writes the JSON itself). One place for how a column is padded
// and how the values every report shares (stability, a state) are written, so that the commands
// print them alike; numbers are core/text.hpp's.

#include <complex>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibromap/core/text.hpp"

namespace vibromap {

class JsonWriter;

// ---- columns ----------------------------------------------------------------------------

// s with spaces after (pad_right: left-aligned) or before (pad_left) it, up to `width`.
std::string pad_right(std::string s, std::size_t width);
std::string pad_left(std::string s, std::size_t width);

struct Column {
  std::string_view head;
  std::size_t width;
  bool left = false;  // left-aligned; else right-aligned
};

// One line of a table: each cell after two spaces, padded to its column's width (no newline).
std::string table_line(std::span<const Column> columns, const std::vector<std::string>& cells);
// The line of the columns' heads.
std::string table_head(std::span<const Column> columns);

// ---- values every report shares -----------------------------------------------------------

// A stability flag (1 stable, 0 unstable, negative unknown): "stable", "unstable", "unknown".
std::string stability_text(int stable);

// The same flag in JSON: true, false, or null when unknown.
JsonWriter& write_stable_json(JsonWriter& w, int stable);

// A state (x1, x2, v1, v2) in JSON: an array of four numbers.
JsonWriter& write_state_json(JsonWriter& w, const Eigen::Vector4d& x);

// The key "multipliers" and Floquet multipliers as an array of [re, im] pairs.
JsonWriter& write_multipliers_json(JsonWriter& w, const std::vector<std::complex<double>>& mu);

// The key "strobe_x1" and the x1 of each stroboscopic state, an array of numbers.
JsonWriter& write_strobe_x1_json(JsonWriter& w, const std::vector<Eigen::Vector4d>& strobe);

}  // namespace vibromap
