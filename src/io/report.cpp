// The reporter: see include/vibromap/io/report.hpp.

#include "vibromap/io/report.hpp"

#include <array>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "vibromap/io/json_writer.hpp"

namespace vibromap {

std::string pad_right(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

std::string pad_left(std::string s, std::size_t width) {
  if (s.size() < width) s.insert(0, width - s.size(), ' ');
  return s;
}

std::string table_line(std::span<const Column> columns, const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t c = 0; c < columns.size() && c < cells.size(); ++c) {
    line += "  ";
    line += columns[c].left ? pad_right(cells[c], columns[c].width) : pad_left(cells[c], columns[c].width);
  }
  return line;
}

std::string table_head(std::span<const Column> columns) {
  std::vector<std::string> heads;
  for (const Column& c : columns) heads.emplace_back(c.head);
  return table_line(columns, heads);
}

std::string stability_text(int stable) {
  if (stable == 1) return "stable";
  if (stable == 0) return "unstable";
  return "unknown";
}

JsonWriter& write_stable_json(JsonWriter& w, int stable) { return stable < 0 ? w.null() : w.value(stable == 1); }

JsonWriter& write_state_json(JsonWriter& w, const Eigen::Vector4d& x) {
  w.begin_array();
  for (int i = 0; i < 4; ++i) w.value(x[i]);
  return w.end_array();
}

JsonWriter& write_multipliers_json(JsonWriter& w, const std::vector<std::complex<double>>& mu) {
  w.key("multipliers").begin_array();
  for (const auto& m : mu) w.begin_array().value(m.real()).value(m.imag()).end_array();
  return w.end_array();
}

JsonWriter& write_strobe_x1_json(JsonWriter& w, const std::vector<Eigen::Vector4d>& strobe) {
  w.key("strobe_x1").begin_array();
  for (const Eigen::Vector4d& x : strobe) w.value(x[0]);
  return w.end_array();
}

std::string stopped_note(const FarmFigures& farm) {
  return farm.stopped_by.empty() ? std::string() : cat("  (stopped by ", farm.stopped_by, ": go on with --resume)");
}

}  // namespace vibromap
