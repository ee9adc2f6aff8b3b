#pragma once
// The reporter: the small pieces every command's stdout is made of, tables for people and JSON
// for scripts (io/json_writer.hpp writes the JSON itself). One place for how a column is padded
// and how the values several reports share (stability, a state, Floquet multipliers, strobes, a
// campaign farm's figures) are written, so that the commands print them alike; numbers are
// core/text.hpp's. Each command's own output is io/<kind>_output.hpp, built from these.

#include <complex>
#include <cstddef>
#include <cstdint>
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

// ---- a campaign's work farm ---------------------------------------------------------------

// What a campaign's work farm did, as its summary prints it: the farm's own report
// (parallel/farm.hpp's FarmReport, which io does not see) copied by the command, with the stop
// signal by name.
struct FarmFigures {
  std::uint64_t items = 0;           // of the campaign
  std::uint64_t items_resumed = 0;   // done before this run
  std::uint64_t items_computed = 0;  // stored by this run
  bool complete = false;             // every item done, no stop signal
  int ranks = 1;
  double wall_s = 0.0;               // the farm's time, s
  double items_per_s = 0.0;          // items computed by this run per second of the farm's time
  int checkpoints = 0;               // periodic checkpoints (the final one excluded)
  double checkpoint_s = 0.0;         // time in periodic checkpoints, s
  double checkpoint_max_s = 0.0;     // the longest checkpoint, the final one included, s
  double final_checkpoint_s = 0.0;   // the final checkpoint, s
  long requests = 0;                 // requests rank 0 served for the other ranks
  double request_s = 0.0;            // rank 0's time serving them, s
  std::string stopped_by;            // the signal that stopped the run ("SIGUSR1"); empty: none
};

// "  (stopped by SIGUSR1: go on with --resume)" after the output's name in a campaign's table
// when a signal stopped it; empty otherwise.
std::string stopped_note(const FarmFigures& farm);

}  // namespace vibromap
