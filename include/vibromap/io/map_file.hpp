#pragma once
// Regime maps: one HDF5 file per sweep, readable by h5py and by xarray (netCDF-4 compatible),
// written cell by cell as a sweep runs (MapWriter) and read back whole or streamed chunk by
// chunk (read_map, scan_map).
//
// Layout (N = number of axes, shape = the axes' lengths, first axis slowest):
//   /<axis>          1-D float64 coordinate per axis, named after the key within its section
//                    (E1, omega, F0, ...), a dimension scale; attributes units, long_name, key
//                    (the full scene key, "forcing.omega") and scale ("lin" | "log")
//   /done            N-D uint8: 1 where the cell has been computed
//   /status          N-D int8: flag_values -1..3, flag_meanings
//                    "not_computed ok budget failed invalid_input"
//   /regime          N-D int8: flag_values -1..8, flag_meanings "not_computed periodic chatter
//                    no_contact permanent_contact quasi_periodic chaotic non_periodic
//                    unresolved failed" (RegimeKind order); with n and k it names (n,k)
//   /stable          N-D int8: flag_values -1..1, flag_meanings "unknown unstable stable":
//                    the periodic orbit's stability from its Floquet multipliers; -1 where
//                    it was not computed (no periodic orbit, not asked, or cell not done)
//   /n, /k           N-D int32 (0 where not periodic or not computed)
//   /wall_s          N-D float64, units s
//   /steady_residual N-D float64, units 1
//   /<quantity>      N-D, only for the scene's [sweep] store list, with units and long_name
//                    from the quantity catalogue (core/quantities.hpp): int64 for the integer
//                    quantities, float64 for the others. A quantity whose long_name ends in
//                    "(NaN where not computed)" (max_multiplier, lyapunov) is NaN also in
//                    cells done where the solver did not compute it.
// With a census (a sweep whose scene has [census]; root attribute census_attractors = A > 0):
//   /attractor       1-D int32 coordinate 0..A-1, a dimension scale (the census's attractor index)
//   /attractors      N-D int32: attractors the census lists in the cell (0..A)
//   /soft_fraction, /unresolved_fraction, /unlisted_fraction, /budget_fraction (the initial
//                    states followed to analysis.max_periods, no early decision)   N-D float64, units 1
//   /basin_entropy   N-D float64: -sum f ln f over the cell's outcomes' shares (basin_entropy.hpp)
//   /attractor_<q>   (N+1)-D, shape + (A,): per (cell, attractor): regime, stable, hertz_valid,
//                    from_rest, soft, transient (int8 flags, -1 where the cell lists fewer attractors),
//                    n, k (int32), T_con, k_con, F_max, z_ratio, max_floquet, fraction,
//                    fraction_stderr, and x1, x2, v1, v2 (the first stroboscopic state; the
//                    other n - 1 follow by the period map; NaN when none), float64 NaN where
//                    not listed. These are what a map keeps of a CellResult's census
//                    attractors (core/analysis/census/census.hpp's Attractor): read back, an attractor
//                    has its first min(n, 4) stroboscopic states (none for a non-periodic one) and its other fields at their
//                    defaults; a listed attractor whose regime or flag holds -1 is malformed.
//   With census.shock (root attribute census_shock = 1), per (cell, attractor) the minimal critical
//   shock (core/analysis/census/critical_shock.hpp): /attractor_shock (float64, motion scales; NaN
//   where none was found, not listed or not looked for), /attractor_shock_status (int8: -1 not
//   listed, then ShockStatus order: not_computed found none not_periodic failed),
//   /attractor_shock_to (int32: index of the attractor it leads to; -2 one the cell does not list,
//   -1 none), /attractor_shock_to_regime (int8, regime codes), /attractor_shock_strobe (int32: which
//   stroboscopic state was perturbed, -1 none), /attractor_shock_dx1, _dx2 (m), _dv1, _dv2 (m/s)
//   (float64, NaN where none).
//   /period_start, /state  coordinates (S = kMapStrobePoints = 4; x1 x2 v1 v2) of
//   /attractor_strobe (N+3)-D, shape + (A, S, 4) float64: the attractor's first S period-start
//                    states (NaN past its period; read back, an attractor has min(n, S) of them)
//   /family, /family_flags  shape + (A) int32, int8: the attractor's family across the map and
//                    its flags, -1 until the family pass (io/map_families.hpp) writes them; no
//                    CellResult member holds them, so writing cells leaves them alone
//   /families        the family table, rewritten by each family pass (not covered by the seal)
//   The ordinary datasets then describe the attractor the rest state reaches.
// Float datasets hold NaN (their _FillValue) where done == 0; integer ones hold 0, and
// regime/status/stable -1. So a NaN alone does not say whether a cell was reached: /done does.
// Root attributes: title, Conventions ("CF-1.8"), vibromap_version, scene (the scene text),
// identity (what --resume compares: the canonical cell-defining values), ranks, cells_total,
// cells_done, complete (0 | 1; both brought up to date when a run ends), stored (the quantity
// names, space separated), census_attractors (A, 0 without a census), steady, hertz_limit,
// soft_kcon (MapLayout's), with sweep.refine the refine_* attributes (MapLayout, RefineFigures),
// then version (the map format's, io/file_format.hpp) and last attribute_checksum (below).
//
// Attribute checksum: chunks have Fletcher32, attributes do not (a string attribute lives in
// HDF5's global heap, which has no checksum: one flipped byte there emptied title, Conventions
// and vibromap_version of a map that was then resumed as if whole). So the root attribute
// attribute_checksum = "crc32 XXXXXXXX; not covered: cells_done complete ranks" holds the CRC-32
// of every attribute of the file and every dataset's type, shape and dimension scales
// (src/io/attribute_seal.hpp documents the record), written when the map is made. Every reader
// (resume(), read_map_layout(), scan_map(), read_map(): --resume, the optimiser's seeding map;
// vibromap.files (postprocess/vibromap)) checks, before reading any value, the map's format version (a map
// of another version, older or newer, is refused: FileVersionError, exit 2) and then the seal,
// and refuses a map that fails it as damaged: IoError "<path>: damaged: its attributes fail their
// checksum (...); make it again with --overwrite" (exit 4, as a damaged coordinate), never "made
// by another run"; a map without the seal is damaged too. The three progress attributes are not
// covered: finish() rewrites them in place, and readers take the counts from /done.
//
// Storage, and why a run killed at any instant loses nothing that was checkpointed:
//   - Every dataset is chunked and carries HDF5's Fletcher32 checksum filter (verified by HDF5,
//     h5py and netCDF-4 on every read): a damaged byte makes its chunk unreadable instead of
//     returning a wrong number.
//   - The chunks of the N-D datasets are runs of consecutive cells in flat order (the trailing
//     axes whole, about kMapChunkCells cells), so the cells handed out together land in one or
//     two chunks, and every chunk is a contiguous range of flat indices.
//   - Every chunk is allocated, and its fill values written, when the file is made: the file's
//     size is known up front (file_bytes), and writing cells never changes the file's structure.
//   - Cells are written into the data datasets as they arrive: a piece that fills its chunk at
//     once, the others (an adaptive map's scattered points, the short runs between them) staged
//     and written a chunk at a time (the chunk read, the cells set, the chunk written whole; at
//     under half a chunk of cells staged). checkpoint() flushes them and
//     syncs the file, and only then sets /done for them (flushed and synced again): /done is
//     never ahead of the data. A chunk torn by a kill in the middle of its write fails its
//     checksum; resume() wipes such chunks and computes their cells again.
// Memory: a writer holds HDF5's chunk cache, one chunk-sized buffer per dataset, the cells staged
// and the ranges of the cells written since the last checkpoint, never a whole dataset.

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "vibromap/core/grid.hpp"
#include "vibromap/core/quantities.hpp"
#include "vibromap/io/file_format.hpp"

namespace vibromap {

// Cells per chunk of the N-D datasets, about (a chunk is 256 KiB of float64).
constexpr std::uint64_t kMapChunkCells = 32768;

// What fixes a map before any cell is computed.
struct MapLayout {
  Grid grid;
  std::vector<Quantity> stored;  // optional quantities kept in the file
  std::string scene_text;        // provenance: the scene after overrides
  std::string identity;          // what --resume compares (one "key = value" line per cell-defining key)
  std::size_t attractors = 0;    // census: the attractor dimension's length (0: no census)
  // What the cells' answers mean (root attributes, for readers and pictures): analysis.steady
  // ("follow": the motion from the initial state; "shooting": some stable orbit; "integrate":
  // brute force), and the Hertz limit and soft threshold of the soft flag.
  std::string steady = {};
  double hertz_limit = 0.05;
  double soft_kcon = 10.0;
  // analysis.fragility (> 0: the map has the dataset fragile and the root attribute fragility;
  // 0: neither, as before the option existed).
  double fragility = 0.0;
  // Adaptive maps (sweep.refine > 0; docs/design-refine.md): the grid above is the fine grid,
  // the map has the datasets computed and level, and root attributes refine_levels, refine_on
  // (the quantities, space separated), refine_audit_fraction, and the figures RefineFigures
  // holds (written by finish(), not covered by the attribute checksum).
  int refine_levels = 0;
  std::string refine_on = {};
  double refine_audit = 0.0;
  bool refine_speckle = false;  // root attribute refine_speckle (0 | 1)
  // Census maps with census.shock: the /attractor_shock* datasets, root attribute census_shock = 1
  // (absent without them).
  bool census_shock = false;
};

// What an adaptive map's run did: points solved (per level, then in all), inherited, audited
// and found to differ from what they inherited, and the 95 % upper bound on that rate.
struct RefineFigures {
  std::vector<std::uint64_t> solved_per_level;  // [0..L]
  std::uint64_t solved = 0, inherited = 0, audited = 0, mismatches = 0;
  double mismatch_bound = 1.0;
  std::uint64_t whole_blocks = 0;  // coarse cells solved whole (speckle)
};

// The root attributes an adaptive map's figures are written to (refine_solved, ...), and how
// they read back (all zero and bound 1 in a map whose run has not finished; absent: a uniform map).
std::vector<std::string> refine_figure_attributes();

// Cells [begin, end) in flat order.
struct CellSpan {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
};

// What resume() found damaged and wiped: its cells are no longer done.
struct MapRepair {
  std::uint64_t chunks = 0;              // damaged chunks (counted once over the datasets)
  std::uint64_t cells = 0;               // cells in them that were done and will be recomputed
  std::vector<std::string> datasets;     // the datasets where damage was found
};

class NewFile;  // io/output_file.hpp

class MapWriter {
 public:
  // The bytes a new map of `layout` takes on disk, about (every chunk is allocated up front).
  static std::uint64_t file_bytes(const MapLayout& layout);
  // Makes a new map file at `path`: every dataset, allocated and filled, in a new file beside
  // it (io/output_file.hpp) that is synced and renamed over `path` (replacing a regular file
  // only), then opened to be filled. Throws IoError naming the path; a partly made new file is
  // removed and an existing `path` left untouched.
  static MapWriter create(const std::string& path, const MapLayout& layout, int ranks);
  // Makes a new map in the new file `out` and opens it to be filled; the caller commits `out`
  // once the map is finished (a map written whole: write_map).
  static MapWriter create_in(NewFile& out, const MapLayout& layout, int ranks);
  // Opens a map to go on filling it: checks its layout, reads every chunk of every dataset to
  // verify its checksum, wipes damaged chunks (repair()), counts the cells done and calls
  // visit_done(flat index, cell) for each (resume's counts of regimes). Throws FileVersionError for a
  // map of another format version, IoError naming the path and what is wrong when it is not a
  // map, a value is out of range or its axes are damaged.
  static MapWriter resume(const std::string& path, const std::function<void(std::uint64_t, const CellResult&)>& visit_done = {});

  MapWriter(MapWriter&&) noexcept;
  MapWriter& operator=(MapWriter&&) noexcept;
  ~MapWriter();

  const std::string& path() const;
  const MapLayout& layout() const;
  std::uint64_t cells_done() const;  // as recorded in /done (the last checkpoint)
  const MapRepair& repair() const;

  // The cells not done at or after `from`, ascending, at most `max` of them, appended to `out`;
  // returns where the scan stopped (cells when none are left). Reads /done a window at a time.
  std::uint64_t pending(std::uint64_t from, std::uint64_t max, std::vector<CellSpan>& out);
  // Writes the results of cells [first, first + cells.size()) (not done until the checkpoint;
  // staged when they fill no chunk: in the file by the checkpoint, or by read_chunk of their chunk).
  void write(std::uint64_t first, std::span<const CellResult> cells);
  // The cells of the chunk that holds cell `flat`, as written so far (a cell not written holds the
  // fill values); returns the chunk's span. Throws IoError when the chunk fails to read.
  CellSpan read_chunk(std::uint64_t flat, std::vector<CellResult>& out);
  // Makes the cells written since the last checkpoint durable and done (see the file comment).
  void checkpoint();
  // The last checkpoint, then the root attributes cells_done, complete and ranks (and an adaptive
  // map's figures, when given); closes.
  void finish(int ranks, const RefineFigures* refine = nullptr);

 private:
  struct Impl;
  explicit MapWriter(std::unique_ptr<Impl> impl);
  static std::unique_ptr<Impl> open_for_writing(const std::string& path);
  static MapWriter open_new(const std::string& path, const MapLayout& layout);
  void verify_and_repair(const std::function<void(std::uint64_t, const CellResult&)>& visit_done);
  void write_run(std::uint64_t first, std::span<const CellResult> cells);
  void flush_staged();
  void write_staged(const CellSpan& chunk, std::size_t from, std::size_t to);
  void mark_done(const std::vector<CellSpan>& spans);
  std::unique_ptr<Impl> impl_;
};

// A whole map in memory (small maps: tests, the Python samples, seeds of small sweeps).
struct SweepMap {
  Grid grid;
  std::vector<Quantity> stored;     // optional quantities kept in the file
  std::vector<CellResult> cells;    // grid.size() records, flat index order
  std::vector<std::uint8_t> done;   // grid.size() flags
  std::string scene_text;           // provenance
  std::string identity;             // what --resume compares
  int ranks = 1;                    // MPI ranks of the run
  std::size_t attractors = 0;       // census: the attractor dimension's length (0: no census)
};

// Writes a whole map (create, every done cell, finish) to `path + ".tmp"`, renamed to `path`
// when complete: a failure leaves no file and an existing `path` untouched. Throws IoError.
void write_map(const std::string& path, const SweepMap& map);

// The layout of the map at `path` (its axes, stored quantities, scene and identity). Throws
// FileVersionError for a map of another format version (as every reader below does), IoError
// naming the path when it is not a readable map.
MapLayout read_map_layout(const std::string& path);

// Streams the map at `path` chunk by chunk: visit(flat index, cell) for every cell done, in flat
// order; memory stays one chunk per dataset. Throws IoError naming the path and the dataset when
// a chunk is damaged (its checksum fails) or a value is out of its range.
void scan_map(const std::string& path, const std::function<void(std::uint64_t, const CellResult&)>& visit);

// Reads a whole map (every value exactly as written; NaN stays NaN). Records of cells not done
// are default CellResult, and so are optional quantities not stored. Throws IoError naming the
// path and what is missing, malformed or damaged.
SweepMap read_map(const std::string& path);

}  // namespace vibromap
