// Tests of what every reader checks first in vibromap's HDF5 files (src/io/attribute_seal.hpp),
// on real maps and basins files: the format version (io/file_format.hpp): a file of another
// version, older or newer or without one, is refused by every reader in one line naming the file
// and both versions, before the seal is looked at; and the attribute checksum: a byte flipped
// inside an attribute's value (found in the file by searching for the value's text: the title,
// the scene, the identity, an axis's long_name, a dataset's flag_meanings) makes every reader
// refuse the file as damaged, before any identity is compared; the progress attributes a finished
// run rewrites do not break the seal; a file without a seal is damaged.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "attribute_seal.hpp"
#include "support/temp_dir.hpp"
#include "support/thrown.hpp"
#include "vibromap/io/basins_file.hpp"
#include "vibromap/io/file_format.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/map_file.hpp"

namespace vibromap {
namespace {

using test::TempDir;
using test::thrown;

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Flips the low bit of the byte `at` bytes into the first occurrence of `needle` in the file
// (a string attribute's value is stored as its bytes, so the value changes by one character).
// Returns the offset flipped; fails the test when the needle is not in the file exactly once.
std::size_t flip_inside(const std::string& path, std::string_view needle, std::size_t at = 0) {
  std::string data = bytes_of(path);
  const std::size_t where = data.find(needle);
  EXPECT_NE(where, std::string::npos) << "'" << needle << "' not in " << path;
  EXPECT_EQ(data.find(needle, where + 1), std::string::npos) << "'" << needle << "' twice in " << path;
  if (where == std::string::npos) return 0;
  data[where + at] = static_cast<char>(data[where + at] ^ 0x01);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
  return where + at;
}

// The message of the Error each map reader throws for the map at `path` ("" for one that throws
// none): resume, read_map, read_map_layout, scan_map.
template <class Error>
std::vector<std::string> map_reader_errors(const std::string& path) {
  return {thrown<Error>([&] { MapWriter::resume(path); }), thrown<Error>([&] { read_map(path); }),
          thrown<Error>([&] { read_map_layout(path); }),
          thrown<Error>([&] { scan_map(path, [](std::uint64_t, const CellResult&) {}); })};
}

// 3 x 2 over E1 (log) and R1 (lin); cell i done unless i == 4; k_con = i + 1.
SweepMap small_map() {
  SweepMap map;
  map.grid = Grid({{"contact.E1", "E1", "Pa", "Young's modulus of body 1", {2e4, 1e7, 2.1e11}, AxisScale::log},
                   {"contact.R1", "R1", "m", "radius of curvature of body 1", {0.5, 2.0}, AxisScale::lin}});
  map.stored = {Quantity::k_con};
  for (std::size_t i = 0; i < map.grid.size(); ++i) {
    CellResult c;
    c.status = 0;
    c.regime = 0;
    c.n = c.k = 1;
    c.k_con = static_cast<double>(i + 1);
    map.cells.push_back(i == 4 ? CellResult{} : c);
    map.done.push_back(i == 4 ? 0 : 1);
  }
  map.scene_text = "[system]\nm2 = 310.0  # scene-text-marker\n";
  map.identity = "system.m2 = 310 # identity-marker\n";
  return map;
}

class AttributeSeal : public TempDir {};

TEST_F(AttributeSeal, AFreshMapVerifiesAndStaysVerifiedAfterAFinishRewritesItsProgress) {
  const std::string path = file("m.h5");
  write_map(path, small_map());
  {
    const Hdf5File f(path);
    EXPECT_NO_THROW(detail::verify_file(f, kMapFormat));
    EXPECT_EQ(f.read_int_attribute("version"), kMapFormat.version);
    EXPECT_EQ(f.read_string_attribute("attribute_checksum").substr(0, 6), "crc32 ");
    EXPECT_NE(f.read_string_attribute("attribute_checksum").find("; not covered: cells_done complete ranks"),
              std::string::npos);
  }
  MapWriter w = MapWriter::resume(path);
  EXPECT_EQ(w.cells_done(), 5u);
  w.finish(7);  // rewrites cells_done, complete and ranks: not covered, so the seal still holds
  EXPECT_EQ(read_map(path).ranks, 7);
  EXPECT_EQ(read_map(path).cells[5].k_con, 6.0);
}

TEST_F(AttributeSeal, AByteFlippedInsideAnyAttributeValueIsDamageForEveryMapReader) {
  // Root strings (global heap), a dataset's string (an axis's long_name, regime's flag_meanings).
  for (const std::string_view needle : {std::string_view("vibromap regime map"), std::string_view("CF-1.8"),
                                        std::string_view("scene-text-marker"), std::string_view("identity-marker"),
                                        std::string_view("radius of curvature of body 1"),
                                        std::string_view("not_computed periodic chatter")}) {
    SCOPED_TRACE(std::string(needle));
    const std::string path = file("m.h5");
    write_map(path, small_map());
    flip_inside(path, needle, 2);
    const std::string want = path + ": damaged: its attributes fail their checksum (attribute_checksum says crc32 ";
    for (const std::string& message : map_reader_errors<IoError>(path)) {
      EXPECT_EQ(message.substr(0, want.size()), want);
      EXPECT_NE(message.find("); make it again with --overwrite"), std::string::npos) << message;
    }
  }
}

TEST_F(AttributeSeal, AnObjectHeaderChunkThatFailsItsChecksumIsDamageForEveryMapReader) {
  // A continuation chunk of an object header ("OCHK", HDF5's version-2 headers) with a byte
  // flipped past its signature fails the chunk's checksum; the data and attributes may not need
  // that chunk, but a walk of the file (h5py's visititems, h5stat) does.
  const std::string path = file("m.h5");
  write_map(path, small_map());
  std::string data = bytes_of(path);
  const std::size_t chunk = data.find("OCHK");
  ASSERT_NE(chunk, std::string::npos) << "no object header continuation chunk in " << path;
  data[chunk + 6] = static_cast<char>(data[chunk + 6] ^ 0x01);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
  const std::string want = path + ": damaged: an object's header cannot be read (";
  for (const std::string& message : map_reader_errors<IoError>(path)) {
    EXPECT_EQ(message.substr(0, want.size()), want) << message;
    EXPECT_NE(message.find("); make it again with --overwrite"), std::string::npos) << message;
  }
}

TEST_F(AttributeSeal, ADamagedSealIsDamageToo) {
  const std::string path = file("m.h5");
  write_map(path, small_map());
  flip_inside(path, "crc32 ", 7);  // the CRC's second hex digit: another digit, or not a hex digit at all
  const std::string message = thrown<IoError>([&] { MapWriter::resume(path); });
  const std::string want = path + ": damaged: its attribute";  // "...s fail their checksum" or "... is not 'crc32 ..."
  EXPECT_EQ(message.substr(0, want.size()), want) << message;
}

TEST_F(AttributeSeal, AMapWithoutItsSealIsDamaged) {
  const std::string path = file("m.h5");
  write_map(path, small_map());
  // In the file: attribute names are kept in HDF5 structures with checksums of their own.
  flip_inside(path, "attribute_checksum", 5);
  const std::string message = thrown<IoError>([&] { MapWriter::resume(path); });
  const std::string want = path + ": damaged: its attributes cannot be read (cannot look up attribute 'attribute_checksum' (";
  EXPECT_EQ(message.substr(0, want.size()), want) << message;
  // Renamed or removed through HDF5 (as a file without those checksums could have it).
  write_map(path, small_map());
  {
    Hdf5File f(path, FileMode::read_write);
    const std::string seal = f.read_string_attribute("attribute_checksum");
    f.remove_attribute("attribute_checksum");
    f.set_attribute("attribute_checksun", seal);
  }
  const std::string none = path + ": damaged: it has no attribute 'attribute_checksum'; make it again with --overwrite";
  EXPECT_EQ(thrown<IoError>([&] { MapWriter::resume(path); }), none);
  {
    Hdf5File f(path, FileMode::read_write);
    f.remove_attribute("attribute_checksun");
  }
  EXPECT_EQ(thrown<IoError>([&] { read_map(path); }), none);
}

TEST_F(AttributeSeal, AMapOfAnotherFormatVersionIsRefusedByEveryReaderNamingBothVersions) {
  // Changed without sealing again: the version is checked first, so it is named, not damage.
  const std::string path = file("m.h5");
  for (const std::int64_t version : {std::int64_t{0}, kMapFormat.version + 1, std::int64_t{-3}}) {
    SCOPED_TRACE(version);
    write_map(path, small_map());
    {
      Hdf5File f(path, FileMode::read_write);
      f.set_attribute("version", version);
    }
    const std::string want = path + ": a regime map of format version " + std::to_string(version) +
                             "; this vibromap reads version 2 only: make the file again with this vibromap";
    for (const std::string& message : map_reader_errors<FileVersionError>(path)) EXPECT_EQ(message, want);
  }
  // Without the attribute (made before files were versioned): version 0.
  write_map(path, small_map());
  {
    Hdf5File f(path, FileMode::read_write);
    f.remove_attribute("version");
  }
  for (const std::string& message : map_reader_errors<FileVersionError>(path))
    EXPECT_EQ(message, path + ": a regime map of format version 0; this vibromap reads version 2 only: make the "
                              "file again with this vibromap");
}

TEST_F(AttributeSeal, AVersionThatIsNotOneIntegerIsDamageAndAFileWithoutAnyIsNotAMap) {
  const std::string path = file("m.h5");
  write_map(path, small_map());
  {
    Hdf5File f(path, FileMode::read_write);
    f.set_attribute("version", "1");
  }
  EXPECT_EQ(thrown<IoError>([&] { read_map(path); }),
            path + ": damaged: its attribute 'version' is not one integer; make it again with --overwrite");
  {
    Hdf5File f(path, FileMode::read_write);
    f.remove_attribute("version");
    f.remove_attribute("vibromap_version");
  }
  EXPECT_EQ(thrown<IoError>([&] { read_map(path); }), path + ": not a vibromap regime map (no root attribute 'version')");
}

TEST_F(AttributeSeal, TheRecordNamesEveryAttributeAndEveryDatasetLayout) {
  const std::string path = file("m.h5");
  write_map(path, small_map());
  const Hdf5File f(path);
  const std::string record = detail::attribute_record(f, {"cells_done", "complete", "ranks"});
  // field(path) field(name) kind field(value): the format attribute_seal.hpp documents.
  EXPECT_NE(record.find("1:/5:title" "s19:vibromap regime map"), std::string::npos);
  EXPECT_NE(record.find("1:/7:version" "i1:" + std::to_string(kMapFormat.version)), std::string::npos);
  EXPECT_NE(record.find("3:/E15:units" "s2:Pa"), std::string::npos);
  EXPECT_NE(record.find("6:/k_con0:" "l" "15:<f8 3x2 /E1;/R1"), std::string::npos);
  EXPECT_NE(record.find("7:/regime11:flag_values" "i20:-1,0,1,2,3,4,5,6,7,8"), std::string::npos);
  EXPECT_NE(record.find("3:/E10:" "l" "6:<f8 3 "), std::string::npos) << "a scale has no scale of its own";
  EXPECT_NE(record.find("5:/done0:" "l" "15:|u1 3x2 /E1;/R1"), std::string::npos);
  EXPECT_EQ(record.find("cells_done"), std::string::npos);
  EXPECT_EQ(record.find("DIMENSION_LIST"), std::string::npos);
  EXPECT_EQ(record.find("attribute_checksum"), std::string::npos);
}

BasinsContent small_basins() {
  BasinsContent c;
  c.scene_text = "[system]\nm2 = 310.0\n";
  c.identity = "basins.plane = x1,v1 # identity-marker\n";
  c.plane.vars = {0, 2};
  c.plane.axes = {std::vector<double>{-0.01, 0.0, 0.01}, std::vector<double>{-0.1, 0.1}};
  c.plane.fixed = Eigen::Vector4d(0.0, 0.05, 0.0, 0.0);
  c.labels.assign(6, kNotComputedLabel);
  c.done.assign(6, 0);
  return c;
}

TEST_F(AttributeSeal, ABasinsFileIsSealedAndAFlippedAttributeByteIsDamage) {
  for (const std::string_view needle :
       {std::string_view("identity-marker"), std::string_view("vibromap basins: the attractor"),
        std::string_view("not_computed overlap unlisted")}) {
    SCOPED_TRACE(std::string(needle));
    const std::string path = file("b.h5");
    write_basins_file(path, small_basins());
    EXPECT_EQ(read_basins_file(path).identity, small_basins().identity);
    flip_inside(path, needle, 1);
    const std::string want = path + ": damaged: its attributes fail their checksum (attribute_checksum says crc32 ";
    const std::string message = thrown<IoError>([&] { read_basins_file(path); });
    EXPECT_EQ(message.substr(0, want.size()), want);
  }
}

TEST_F(AttributeSeal, ABasinsFileCarriesItsVersionAndAnotherIsRefused) {
  const std::string path = file("b.h5");
  write_basins_file(path, small_basins());
  EXPECT_EQ(Hdf5File(path).read_int_attribute("version"), kBasinsFormat.version);
  {
    Hdf5File f(path, FileMode::read_write);
    f.set_attribute("version", kBasinsFormat.version + 1);
  }
  EXPECT_EQ(thrown<FileVersionError>([&] { read_basins_file(path); }),
            path + ": a basins file of format version 2; this vibromap reads version 1 only: make the file again "
                   "with this vibromap");
}

}  // namespace
}  // namespace vibromap
