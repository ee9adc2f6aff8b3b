// Tests of the trajectory writer (io/trajectory_file.hpp) and of the HDF5 layer under it
// (io/hdf5_file.hpp): round trips compared bit for bit, attributes, atomic replacement and
// the one-line IoError on failure.
//
// Reference trajectory: an analytic harmonic motion sampled on a uniform grid, so every
// written number is known independently of the solver (which this test does not use).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <unistd.h>
#include <vector>

#include "support/temp_dir.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/trajectory_file.hpp"

namespace vibromap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

// Harmonic reference motion: x1 = a1 sin(omega t), x2 = D + a2 cos(omega t), velocities the
// exact derivatives, Fc a half-sine pulse, F = F0 cos(omega t); `samples` points over `periods` T.
PointSummary harmonic_summary(int samples_per_period, int periods) {
  constexpr double kOmega = 7.23, kD = 0.05, kA1 = 0.02, kA2 = 0.01, kF0 = 500.0, kFmax = 1.0e5;
  PointSummary s;
  s.status = SolveStatus::ok;
  s.regime = Regime{RegimeKind::periodic, 1, 1};
  s.T = 2.0 * std::numbers::pi / kOmega;
  s.T_con = 7.81e-4;
  s.k_con = s.T / s.T_con;
  const int n = samples_per_period * periods + 1;
  for (int i = 0; i < n; ++i) {
    const double t = s.T * i / samples_per_period;
    const double phase = kOmega * t;
    const double pulse = std::sin(phase);
    s.trajectory.push_back({t, kA1 * std::sin(phase), kD + kA2 * std::cos(phase), kA1 * kOmega * std::cos(phase),
                            -kA2 * kOmega * std::sin(phase), pulse > 0.0 ? kFmax * pulse : 0.0, kF0 * std::cos(phase)});
  }
  return s;
}

std::vector<double> column(const PointSummary& s, double TrajectorySample::*member) {
  std::vector<double> v;
  for (const auto& sample : s.trajectory) v.push_back(sample.*member);
  return v;
}

const std::string kScene =
    "# Table 1 of the source paper\n[system]\nm1 = 1000.0\nm2 = 100.0\n[contact]\nE1 = 2.099e11\n"
    "note = \"UTF-8: \xce\xbb F0 cos(\xcf\x89 t)\"\n";

// ---- write_trajectory -------------------------------------------------------------------

using TrajectoryFile = TempDir;

TEST_F(TrajectoryFile, RoundTripsEverySampleExactly) {
  const PointSummary s = harmonic_summary(64, 2);
  const std::string path = file("traj.h5");
  write_trajectory(path, s, kScene);

  const Hdf5File f(path);
  const std::vector<std::pair<const char*, double TrajectorySample::*>> columns = {
      {"t", &TrajectorySample::t},   {"x1", &TrajectorySample::x1}, {"x2", &TrajectorySample::x2},
      {"v1", &TrajectorySample::v1}, {"v2", &TrajectorySample::v2}, {"Fc", &TrajectorySample::Fc},
      {"F", &TrajectorySample::F}};
  for (const auto& [name, member] : columns) {
    const Dataset d = f.open_dataset(name);
    EXPECT_EQ(d.shape(), Shape{129}) << name;
    EXPECT_EQ(d.read_double(), column(s, member)) << name;  // bit-exact: float64 in, float64 out
  }
  // Spot values against the analytic formula (not only against what was written).
  const std::vector<double> x1 = f.open_dataset("x1").read_double();
  EXPECT_DOUBLE_EQ(x1[16], 0.02 * std::sin(7.23 * s.T * 16 / 64));  // quarter period: 0.02
  EXPECT_NEAR(x1[16], 0.02, 1e-15);
  EXPECT_DOUBLE_EQ(f.open_dataset("F").read_double()[64], 500.0 * std::cos(2.0 * std::numbers::pi));
}

TEST_F(TrajectoryFile, DatasetsCarryUnits) {
  const std::string path = file("traj.h5");
  write_trajectory(path, harmonic_summary(8, 1), kScene);
  const Hdf5File f(path);
  const std::vector<std::pair<const char*, const char*>> units = {{"t", "s"},     {"x1", "m"},   {"x2", "m"}, {"v1", "m/s"},
                                                                  {"v2", "m/s"}, {"Fc", "N"}, {"F", "N"}};
  for (const auto& [name, unit] : units) EXPECT_EQ(f.open_dataset(name).read_string_attribute("units"), unit) << name;
}

TEST_F(TrajectoryFile, RootAttributesDescribeThePoint) {
  const PointSummary s = harmonic_summary(8, 1);
  const std::string path = file("traj.h5");
  write_trajectory(path, s, kScene);
  const Hdf5File f(path);
  EXPECT_EQ(f.read_double_attribute("T"), s.T);
  EXPECT_EQ(f.read_string_attribute("regime"), "(1,1)");
  EXPECT_EQ(f.read_int_attribute("n"), 1);
  EXPECT_EQ(f.read_int_attribute("k"), 1);
  EXPECT_EQ(f.read_double_attribute("T_con"), 7.81e-4);
  EXPECT_EQ(f.read_double_attribute("k_con"), s.T / 7.81e-4);
  EXPECT_EQ(f.read_string_attribute("scene"), kScene);  // multi-line, UTF-8, unchanged
  EXPECT_EQ(f.read_string_attribute("vibromap_version"), VIBROMAP_VERSION);
}

TEST_F(TrajectoryFile, NonPeriodicRegimeIsLabelledByKind) {
  PointSummary s = harmonic_summary(8, 1);
  s.regime = Regime{RegimeKind::chatter, 0, 0};
  const std::string path = file("traj.h5");
  write_trajectory(path, s, kScene);
  const Hdf5File f(path);
  EXPECT_EQ(f.read_string_attribute("regime"), "chatter");
  EXPECT_EQ(f.read_int_attribute("n"), 0);
}

TEST_F(TrajectoryFile, MissingDirectoryThrowsIoErrorNamingPathAndLeavesNoFile) {
  const std::string path = file("no_such_dir/traj.h5");
  try {
    write_trajectory(path, harmonic_summary(8, 1), kScene);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;  // one line
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(TrajectoryFile, UnwritableDirectoryThrowsIoErrorAndLeavesNoFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string path = (locked / "traj.h5").string();
  EXPECT_THROW(write_trajectory(path, harmonic_summary(8, 1), kScene), IoError);
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(TrajectoryFile, PathThroughARegularFileThrowsIoErrorAndLeavesNoFile) {
  // Works as root too (unlike directory permissions): a regular file cannot hold files.
  const std::string plain = file("plain.txt");
  std::ofstream(plain) << "x\n";
  const std::string path = plain + "/traj.h5";
  try {
    write_trajectory(path, harmonic_summary(8, 1), kScene);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot write here: '" + plain + "' is not a directory");
  }
  EXPECT_TRUE(fs::is_regular_file(plain));
}

TEST_F(TrajectoryFile, OverwritesAnExistingFile) {
  const std::string path = file("traj.h5");
  write_trajectory(path, harmonic_summary(16, 2), kScene);
  PointSummary second = harmonic_summary(4, 1);
  second.regime = Regime{RegimeKind::periodic, 2, 1};
  write_trajectory(path, second, "[system]\n");
  const Hdf5File f(path);
  EXPECT_EQ(f.open_dataset("t").read_double(), column(second, &TrajectorySample::t));
  EXPECT_EQ(f.read_string_attribute("regime"), "(2,1)");
  EXPECT_EQ(f.read_int_attribute("n"), 2);
  EXPECT_EQ(f.read_string_attribute("scene"), "[system]\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(TrajectoryFile, EmptyTrajectoryGivesEmptyDatasets) {
  PointSummary s = harmonic_summary(8, 1);
  s.trajectory.clear();
  const std::string path = file("traj.h5");
  write_trajectory(path, s, kScene);
  const Hdf5File f(path);
  EXPECT_EQ(f.open_dataset("Fc").shape(), Shape{0});
  EXPECT_TRUE(f.open_dataset("Fc").read_double().empty());
}

// When VIBROMAP_SAMPLE_TRAJECTORY names a path (ctest sets it: tests/postprocess_tests.cmake),
// leaves the analytic trajectory there; postprocess/tests checks the Python reader against the
// same formulas (conftest.analytic_trajectory), so writer and reader are tested on one file.
TEST(TrajectoryFileSample, WritesTheSampleForThePythonReader) {
  const char* path = std::getenv("VIBROMAP_SAMPLE_TRAJECTORY");
  if (path == nullptr) GTEST_SKIP() << "VIBROMAP_SAMPLE_TRAJECTORY not set (set by ctest's postprocess tests)";
  write_trajectory(path, harmonic_summary(64, 2), kScene);
  EXPECT_EQ(Hdf5File(path).open_dataset("t").size(), 129u);
}

// ---- the HDF5 layer ---------------------------------------------------------------------

using Hdf5Layer = TempDir;

TEST_F(Hdf5Layer, NdIntegerAndDoubleArraysRoundTrip) {
  const std::string path = file("nd.h5");
  const std::vector<std::int64_t> big = {-3, 0, 1, 2, 1LL << 40, -(1LL << 62)};
  const std::vector<int> small = {1, 2, 3, 4, 5, 6};
  std::vector<double> grid(24);
  for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = 0.1 * static_cast<double>(i) - 1e-300;
  {
    Hdf5File f(path, FileMode::truncate);
    f.write_dataset("big", big, {2, 3});
    f.write_dataset("maps/small", small, {3, 2});  // intermediate group made on the way
    f.write_dataset("maps/grid", grid, {2, 3, 4}, DatasetOptions{{1, 3, 4}, 4});  // chunked + gzip
  }
  const Hdf5File f(path);
  EXPECT_EQ(f.open_dataset("big").shape(), (Shape{2, 3}));
  EXPECT_EQ(f.open_dataset("big").read_int(), big);
  EXPECT_EQ(f.open_group("maps").open_dataset("small").read_int(), (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.open_dataset("maps/small").read_double(), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.open_dataset("maps/grid").shape(), (Shape{2, 3, 4}));
  EXPECT_EQ(f.open_dataset("maps/grid").read_double(), grid);
  EXPECT_TRUE(f.exists("maps/grid"));
  EXPECT_TRUE(f.exists("/maps/grid"));
  EXPECT_TRUE(f.open_group("maps").exists("grid"));
  EXPECT_FALSE(f.exists("maps/nothing"));
  EXPECT_FALSE(f.exists("nothing/grid"));
}

TEST_F(Hdf5Layer, AttributesOnGroupsAndDatasetsAreReplaceable) {
  const std::string path = file("attrs.h5");
  {
    Hdf5File f(path, FileMode::truncate);
    Group g = f.create_group("sweep");
    g.set_attribute("count", 3);
    g.set_attribute("count", std::size_t{7});  // replaces
    g.set_attribute("tol", 1e-10);
    Dataset d = g.write_dataset("x", std::vector<double>{1.0});
    d.set_attribute("units", "m");
  }
  {
    Hdf5File f(path, FileMode::read_write);
    f.open_group("sweep").set_attribute("label", std::string("resumed"));
  }
  const Hdf5File f(path);
  const Group g = f.open_group("sweep");
  EXPECT_EQ(g.read_int_attribute("count"), 7);
  EXPECT_EQ(g.read_double_attribute("count"), 7.0);  // integers read as doubles
  EXPECT_EQ(g.read_double_attribute("tol"), 1e-10);
  EXPECT_EQ(g.read_string_attribute("label"), "resumed");
  EXPECT_EQ(g.open_dataset("x").read_string_attribute("units"), "m");
  EXPECT_TRUE(g.has_attribute("tol"));
  EXPECT_FALSE(g.has_attribute("nothing"));
  EXPECT_THROW(g.read_int_attribute("tol"), IoError);     // a float is not an integer
  EXPECT_THROW(g.read_double_attribute("label"), IoError);  // a string is not a number
  EXPECT_THROW(g.read_string_attribute("count"), IoError);
}

TEST_F(Hdf5Layer, ErrorsAreOneLineNamingFileAndOperationWithNothingOnStderr) {
  const std::string path = file("e.h5");
  {
    Hdf5File f(path, FileMode::truncate);
    f.write_dataset("x", std::vector<double>{1.0, 2.0});
  }
  const Hdf5File f(path);
  ::testing::internal::CaptureStderr();
  std::string message;
  try {
    f.open_dataset("missing");
  } catch (const IoError& e) {
    message = e.what();
  }
  const std::string stderr_text = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(stderr_text, "");  // HDF5's own error stack printing is off
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("open dataset '/missing'"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST_F(Hdf5Layer, OpeningMissingOrForeignFilesThrowsIoError) {
  const std::string missing = file("missing.h5");
  try {
    const Hdf5File f(missing);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot open file for reading (No such file or directory)");
  }
  const std::string text = file("text.h5");
  std::ofstream(text) << "not an HDF5 file\n";
  EXPECT_THROW(Hdf5File{text}, IoError);
}

TEST_F(Hdf5Layer, ShapeMismatchAndDuplicateNamesThrowIoError) {
  Hdf5File f(file("s.h5"), FileMode::truncate);
  EXPECT_THROW(f.write_dataset("x", std::vector<double>{1, 2, 3}, {2, 2}), IoError);
  f.write_dataset("y", std::vector<double>{1, 2, 3});
  EXPECT_THROW(f.write_dataset("y", std::vector<double>{1, 2, 3}), IoError);
}

TEST_F(Hdf5Layer, FailedAtomicWriteKeepsTheOldFileAndRemovesTmp) {
  const std::string path = file("a.h5");
  write_hdf5_atomically(path, [](Hdf5File& f) { f.write_dataset("x", std::vector<double>{1.0}); });
  EXPECT_THROW(write_hdf5_atomically(path,
                                     [](Hdf5File& f) {
                                       f.write_dataset("x", std::vector<double>{2.0});
                                       throw IoError("simulated failure");
                                     }),
               IoError);
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(Hdf5File(path).open_dataset("x").read_double(), std::vector<double>{1.0});
}

}  // namespace
}  // namespace vibromap
