// Tests of MapWriter::resume's repair of damaged chunks (map_file.hpp) where the damage is in a
// census map's per-attractor dataset, whose chunks have one more dimension than the grid's: the
// damaged chunk must be replaced where it is (offset 0 in the attractor dimension), so that the
// map reads back whole afterwards.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "support/temp_dir.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap {
namespace {

using test::TempDir;

constexpr double kMarker = 1.2345678901234567e-3;  // every attractor's T_con: its bytes are found in the file

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// 3 x 2 over E1 and R1 with a census of 2 attractors per cell; every cell done.
SweepMap census_map() {
  SweepMap map;
  map.grid = Grid({{"contact.E1", "E1", "Pa", "Young's modulus of body 1", {2e4, 1e7, 2.1e11}, AxisScale::log},
                   {"contact.R1", "R1", "m", "radius of curvature of body 1", {0.5, 2.0}, AxisScale::lin}});
  map.attractors = 2;
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    CellResult c;
    c.status = 0;
    c.regime = 0;
    c.n = c.k = 1;
    Attractor a;
    a.regime = Regime{RegimeKind::periodic, 1, 1};
    a.T_con = kMarker;
    a.fraction = 0.5;
    c.census = {a, a};
    map.cells.push_back(c);
    map.done.push_back(1);
  }
  map.scene_text = "[census]\n";
  return map;
}

class MapRepair : public TempDir {};

TEST_F(MapRepair, ADamagedPerAttractorChunkIsReplacedWhereItIs) {
  const std::string path = file("census.h5");
  write_map(path, census_map());
  std::string data = bytes_of(path);
  char marker[sizeof kMarker];
  std::memcpy(marker, &kMarker, sizeof kMarker);
  const std::size_t at = data.find(std::string(marker, sizeof marker));  // in /attractor_T_con's only chunk
  ASSERT_NE(at, std::string::npos);
  data[at + 3] = static_cast<char>(data[at + 3] ^ 0x20);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
  {
    MapWriter w = MapWriter::resume(path);
    EXPECT_EQ(w.repair().chunks, 1u);
    EXPECT_EQ(w.repair().datasets, std::vector<std::string>{"attractor_T_con"});
    EXPECT_EQ(w.cells_done(), 0u);
    w.finish(1);
  }
  const SweepMap read = read_map(path);  // no chunk left damaged
  EXPECT_EQ(std::count(read.done.begin(), read.done.end(), 1), 0);
  MapWriter again = MapWriter::resume(path);
  EXPECT_EQ(again.repair().chunks, 0u);
}

}  // namespace
}  // namespace vibromap
