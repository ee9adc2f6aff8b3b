// The streaming map writer (io/map_file.hpp): cells written range by range in any order land
// where they belong, /done follows the data only at checkpoints, every chunk is a contiguous
// run of cells, a damaged byte is caught by the chunk checksums (read_map refuses, resume wipes
// the chunk and recomputing it restores the map), and the file's size is known up front.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "map_fields.hpp"  // src/io: the chunk geometry
#include "support/temp_dir.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap {
namespace {

using test::TempDir;

Axis axis(std::string name, std::vector<double> values) {
  Axis a;
  a.name = name;
  a.key = "contact." + name;
  a.units = "Pa";
  a.long_name = "a test axis";
  a.values = std::move(values);
  return a;
}

std::vector<double> points(int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  std::iota(v.begin(), v.end(), 1.0);
  return v;
}

// A made-up but exact cell result per flat index: every stored field is a function of i.
CellResult cell(std::uint64_t i) {
  CellResult c;
  c.status = static_cast<std::int8_t>(i % 3);
  c.regime = static_cast<std::int8_t>(i % 9);
  c.stable = static_cast<std::int8_t>(static_cast<int>(i % 3) - 1);
  c.n = static_cast<std::int32_t>(i % 7);
  c.k = static_cast<std::int32_t>(i % 5);
  c.wall_s = 1e-3 * static_cast<double>(i);
  c.steady_residual = 1.0 / static_cast<double>(i + 1);
  c.T_con = 0.5 + static_cast<double>(i);
  c.k_con = 1000.0 + static_cast<double>(i);
  c.periods = static_cast<std::int64_t>(i) * 3;
  return c;
}

std::vector<CellResult> cells(std::uint64_t first, std::uint64_t last) {
  std::vector<CellResult> out;
  for (std::uint64_t i = first; i < last; ++i) out.push_back(cell(i));
  return out;
}

MapLayout layout(std::vector<Axis> axes) {
  return {Grid(std::move(axes)), {Quantity::T_con, Quantity::k_con, Quantity::periods}, "[sweep]\n", "identity\n"};
}

void expect_cell(const CellResult& got, std::uint64_t i) {
  const CellResult want = cell(i);
  EXPECT_EQ(got.status, want.status) << i;
  EXPECT_EQ(got.regime, want.regime) << i;
  EXPECT_EQ(got.stable, want.stable) << i;
  EXPECT_EQ(got.n, want.n) << i;
  EXPECT_EQ(got.k, want.k) << i;
  EXPECT_EQ(got.wall_s, want.wall_s) << i;
  EXPECT_EQ(got.T_con, want.T_con) << i;
  EXPECT_EQ(got.k_con, want.k_con) << i;
  EXPECT_EQ(got.periods, want.periods) << i;
}

class MapWriterTest : public TempDir {};

TEST(MapChunks, EveryChunkIsAContiguousRunAndTheyCoverEveryCellOnce) {
  for (const Shape& shape : {Shape{7}, Shape{100000}, Shape{10, 7}, Shape{300, 301}, Shape{5, 11, 3000},
                             Shape{3, 100003}, Shape{2, 3, 4, 5, 6, 7, 8, 9}}) {
    const Shape chunk = detail::map_chunk_shape(shape);
    std::uint64_t cells = 1, per_chunk = 1;
    for (std::size_t d = 0; d < shape.size(); ++d) {
      cells *= shape[d];
      per_chunk *= chunk[d];
      EXPECT_LE(chunk[d], shape[d]);
    }
    EXPECT_LE(per_chunk, std::max<std::uint64_t>(kMapChunkCells, shape.back()));
    const auto spans = detail::chunk_spans(shape, chunk);
    std::uint64_t next = 0;
    for (const CellSpan& s : spans) {
      ASSERT_EQ(s.begin, next) << "chunks follow each other in flat order";
      ASSERT_GT(s.end, s.begin);
      ASSERT_LE(s.end - s.begin, per_chunk);
      next = s.end;
    }
    EXPECT_EQ(next, cells);
  }
}

TEST_F(MapWriterTest, FlatRangesOfAnNdDatasetLandWhereRowMajorOrderPutsThem) {
  const Shape shape{3, 4, 5};
  Hdf5File f(file("flat.h5"), FileMode::truncate);
  DatasetOptions o;
  o.chunk = {1, 2, 5};
  o.fletcher32 = true;
  o.fill_value = -1.0;
  Dataset d = f.create_dataset("x", ElementType::int64, shape, o);
  std::vector<std::int64_t> want(60, -1);
  const std::vector<std::pair<int, int>> ranges = {{7, 43}, {0, 3}, {43, 60}, {5, 6}, {4, 5}};
  for (const auto& [a, b] : ranges) {
    std::vector<std::int64_t> v;
    for (int i = a; i < b; ++i) v.push_back(100 + i), want[static_cast<std::size_t>(i)] = 100 + i;
    d.write_flat(static_cast<std::uint64_t>(a), std::span<const std::int64_t>(v));
  }
  EXPECT_EQ(d.read_int(), want);
  std::vector<double> middle(17);
  d.read_flat(21, std::span<double>(middle));
  for (int i = 0; i < 17; ++i) EXPECT_EQ(middle[static_cast<std::size_t>(i)], want[static_cast<std::size_t>(21 + i)]);
}

TEST_F(MapWriterTest, CellsWrittenInAnyOrderAreDoneOnlyAfterACheckpoint) {
  const MapLayout l = layout({axis("E1", points(40)), axis("E2", points(50))});
  MapWriter w = MapWriter::create(file("m.h5"), l, 2);
  for (const auto& [a, b] : std::vector<std::pair<int, int>>{{100, 400}, {0, 100}, {1500, 2000}, {990, 1010}})
    w.write(static_cast<std::uint64_t>(a), cells(static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(b)));
  EXPECT_EQ(w.cells_done(), 0u);
  std::vector<CellSpan> pending;
  EXPECT_EQ(w.pending(0, 10, pending), 10u) << "written but not checkpointed: still pending";
  w.checkpoint();
  EXPECT_EQ(w.cells_done(), 920u);
  pending.clear();
  w.pending(0, 2000, pending);
  std::uint64_t n = 0;
  for (const CellSpan& s : pending) {
    n += s.end - s.begin;
    for (std::uint64_t i = s.begin; i < s.end; ++i)
      EXPECT_FALSE((i < 400) || (i >= 990 && i < 1010) || i >= 1500) << "done cell " << i << " pending";
  }
  EXPECT_EQ(n, 2000u - 920u);
  w.write(400, cells(400, 990));
  w.write(1010, cells(1010, 1500));
  w.finish(3);
  const SweepMap back = read_map(file("m.h5"));
  EXPECT_EQ(back.ranks, 3);
  EXPECT_EQ(back.identity, "identity\n");
  for (std::uint64_t i = 0; i < 2000; ++i) {
    ASSERT_EQ(back.done[i], 1) << i;
    expect_cell(back.cells[i], i);
  }
}

TEST_F(MapWriterTest, ScatteredSingleCellsLandExactlyAndTheLastValuesWin) {
  // Every 7th cell of a map of several chunks, one at a time in a shuffled order (more than the
  // writer stages at once: it writes them a chunk at a time), one of them twice, those of the
  // second chunk with wrong values then that chunk whole, and a run across the third's edge.
  const MapLayout l = layout({axis("E1", points(300)), axis("E2", points(301))});
  const std::uint64_t total = 300 * 301;
  const auto spans = detail::chunk_spans(l.grid.shape(), detail::map_chunk_shape(l.grid.shape()));
  ASSERT_GE(spans.size(), 3u);
  const CellSpan second = spans[1], third = spans[2];
  MapWriter w = MapWriter::create(file("scattered.h5"), l, 1);
  std::vector<std::uint64_t> order;
  for (std::uint64_t i = 0; i < total; i += 7) order.push_back(i);
  std::shuffle(order.begin(), order.end(), std::mt19937(30));
  std::vector<char> written(total, 0);
  w.write(order[0], cells(order[0] + 1, order[0] + 2));  // wrong values, written again below
  for (const std::uint64_t i : order) {
    const bool in_second = i >= second.begin && i < second.end;
    w.write(i, cells(in_second ? i + 1 : i, (in_second ? i + 1 : i) + 1));
    written[i] = 1;
  }
  w.write(second.begin, cells(second.begin, second.end));
  w.write(third.begin - 50, cells(third.begin - 50, third.begin + 50));
  std::fill(written.begin() + static_cast<std::ptrdiff_t>(second.begin), written.begin() + static_cast<std::ptrdiff_t>(second.end), 1);
  std::fill(written.begin() + static_cast<std::ptrdiff_t>(third.begin - 50), written.begin() + static_cast<std::ptrdiff_t>(third.begin + 50), 1);
  const std::uint64_t n_written = static_cast<std::uint64_t>(std::count(written.begin(), written.end(), 1));
  // Before the checkpoint: the first chunk as written so far, fill values where nothing was.
  std::vector<CellResult> first;
  const CellSpan span = w.read_chunk(3, first);
  ASSERT_EQ(span.begin, 0u);
  ASSERT_EQ(span.end, spans[0].end);
  for (std::uint64_t k = 0; k < span.end; ++k) {
    if (written[k]) {
      expect_cell(first[k], k);
    } else {
      ASSERT_EQ(first[k].status, CellResult{}.status) << k;
      ASSERT_TRUE(std::isnan(first[k].T_con)) << k;
    }
  }
  w.checkpoint();
  std::vector<CellSpan> pending;
  w.pending(0, total, pending);
  std::uint64_t n_pending = 0;
  for (const CellSpan& s : pending)
    for (std::uint64_t i = s.begin; i < s.end; ++i, ++n_pending) ASSERT_FALSE(written[i]) << "cell " << i << " pending";
  EXPECT_EQ(n_pending, total - n_written);
  w.finish(1);
  const SweepMap back = read_map(file("scattered.h5"));
  for (std::uint64_t i = 0; i < total; ++i) {
    ASSERT_EQ(back.done[i], written[i]) << i;
    if (written[i]) expect_cell(back.cells[i], i);
  }
}

TEST_F(MapWriterTest, TheFileSizeIsKnownWhenTheMapIsMade) {
  const MapLayout l = layout({axis("E1", points(300)), axis("E2", points(250))});
  MapWriter::create(file("size.h5"), l, 1).finish(1);
  const double size = static_cast<double>(std::filesystem::file_size(file("size.h5")));
  const double predicted = static_cast<double>(MapWriter::file_bytes(l));
  EXPECT_NEAR(size / predicted, 1.0, 0.05) << size << " bytes on disk, " << predicted << " predicted";
}

// Flips one byte of a float64 value that appears once in the file: the raw chunk of dataset
// T_con holding that value (chunks are stored as they are, with their checksum after them).
void flip_byte_of_value(const std::string& path, double value) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(f)), {});
  const std::string pattern(reinterpret_cast<const char*>(&value), sizeof value);
  const auto at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(pattern, at + 1), std::string::npos) << "the value must appear once";
  f.seekp(static_cast<std::streamoff>(at + 3));
  f.put(static_cast<char>(bytes[at + 3] ^ 0x5A));
}

TEST_F(MapWriterTest, ADamagedByteIsRefusedByReadersAndRepairedByResume) {
  const MapLayout l = layout({axis("E1", points(400)), axis("E2", points(200))});  // 80,000 cells, 3 chunks
  const std::uint64_t cells_total = l.grid.size();
  {
    MapWriter w = MapWriter::create(file("d.h5"), l, 1);
    w.write(0, cells(0, cells_total));
    w.finish(1);
  }
  const std::uint64_t victim = 50'000;  // T_con = 50000.5 appears once
  flip_byte_of_value(file("d.h5"), cell(victim).T_con);
  try {
    read_map(file("d.h5"));
    ADD_FAILURE() << "a damaged map was read";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("dataset '/T_con' is damaged"), std::string::npos) << e.what();
  }
  MapWriter w = MapWriter::resume(file("d.h5"));
  const auto spans = detail::chunk_spans(l.grid.shape(), detail::map_chunk_shape(l.grid.shape()));
  const auto hit = std::find_if(spans.begin(), spans.end(), [&](const CellSpan& s) { return s.begin <= victim && victim < s.end; });
  ASSERT_NE(hit, spans.end());
  EXPECT_EQ(w.repair().chunks, 1u);
  EXPECT_EQ(w.repair().cells, hit->end - hit->begin);
  EXPECT_EQ(w.repair().datasets, std::vector<std::string>{"T_con"});
  EXPECT_EQ(w.cells_done(), cells_total - (hit->end - hit->begin));
  std::vector<CellSpan> pending;
  w.pending(0, cells_total, pending);
  ASSERT_EQ(pending.size(), 1u);
  EXPECT_EQ(pending[0].begin, hit->begin);
  EXPECT_EQ(pending[0].end, hit->end);
  w.write(hit->begin, cells(hit->begin, hit->end));
  w.finish(1);
  const SweepMap back = read_map(file("d.h5"));
  for (std::uint64_t i = 0; i < cells_total; i += 97) expect_cell(back.cells[i], i);
  expect_cell(back.cells[victim], victim);
}

TEST_F(MapWriterTest, ResumeCountsTheDoneCellsOfAStoppedRun) {
  const MapLayout l = layout({axis("E1", points(30)), axis("E2", points(30))});
  {
    MapWriter w = MapWriter::create(file("r.h5"), l, 1);
    w.write(10, cells(10, 500));
    w.checkpoint();
    w.write(600, cells(600, 700));  // lost: no checkpoint after it (a kill now)
  }
  long visited = 0;
  MapWriter w = MapWriter::resume(file("r.h5"), [&](std::uint64_t, const CellResult&) { ++visited; });
  EXPECT_EQ(w.cells_done(), 490u);
  EXPECT_EQ(visited, 490);
  EXPECT_EQ(w.repair().chunks, 0u);
}

}  // namespace
}  // namespace vibromap
