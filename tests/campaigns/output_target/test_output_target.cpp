// A campaign's output (campaigns/output_target.hpp): check_output's rule, the run lock, the one
// wording of a resume refused for another run's file, and the disk check.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "vibromap/campaigns/output_target.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "support/thrown.hpp"

namespace fs = std::filesystem;
using namespace vibromap;
using vibromap::test::thrown;

namespace {

class OutputTargetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vibromap_output_target_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }


  fs::path dir_;
};

TEST_F(OutputTargetTest, ANewOutputIsLockedForTheRunAndTheLockGoesWithIt) {
  const std::string p = path("map.h5");
  {
    const OutputTarget target(p, {.resumable = true, .resume = true});
    EXPECT_FALSE(target.exists());
    EXPECT_FALSE(target.resuming());  // --resume with nothing to resume: a new file
    EXPECT_EQ(target.lock_path(), p + ".lock");
    EXPECT_TRUE(fs::exists(p + ".lock"));
    const std::string second = thrown<SceneError>([&] { OutputTarget again(p, {}); });
    EXPECT_EQ(second.rfind(p + ": another vibromap run is writing it (pid " + std::to_string(::getpid()), 0), 0u)
        << second;
  }
  EXPECT_FALSE(fs::exists(p + ".lock"));
  const OutputTarget unlocked(p, {}, OutputLocking::none);
  EXPECT_EQ(unlocked.lock_path(), "");
  EXPECT_FALSE(fs::exists(p + ".lock"));
}

TEST_F(OutputTargetTest, AnExistingOutputFollowsTheOneRule) {
  const std::string p = path("map.h5");
  std::ofstream(p) << "x";
  EXPECT_EQ(thrown<SceneError>([&] { OutputTarget t(p, {.resumable = true}); }),
            p + ": --output: already exists; use --resume to continue it or --overwrite to replace it");
  EXPECT_FALSE(fs::exists(p + ".lock"));  // refused before the lock file is made
  const OutputTarget resumed(p, {.resumable = true, .resume = true});
  EXPECT_TRUE(resumed.exists() && resumed.resuming());
  EXPECT_EQ(resumed.read([](const std::string& name) { return name; }), p);
}

TEST_F(OutputTargetTest, AnotherRunsFileIsRefusedNamingTheFirstFourDifferingKeys) {
  const std::string p = path("map.h5");
  const OutputTarget target(p, {.resumable = true, .resume = true}, OutputLocking::none);
  const std::string file = "a = 1\nb = 1\nc = 1\nd = 1\ne = 1\nf = 1\ng = 1\n";
  const std::string scene = "a = 2\nb = 2\nc = 2\nd = 2\ne = 2\nf = 1\ng = 2\n";
  EXPECT_EQ(thrown<SceneError>([&] { target.check_identity(file, scene, "s.toml"); }),
            p + ": --resume: made by another run than s.toml: a (1 in the file, 2 in the scene), b (1 in the file, "
                "2 in the scene), c (1 in the file, 2 in the scene), d (1 in the file, 2 in the scene) and 2 more; "
                "use --overwrite to start again, or another --output");
  EXPECT_EQ(thrown<SceneError>([&] { target.check_identity(file, file, "s.toml", "the grid"); }),
            p + ": --resume: made by another run than s.toml: the grid; use --overwrite to start again, or another "
                "--output");
  EXPECT_EQ(thrown<SceneError>([&] { target.check_identity(file, file, "s.toml"); }), "");  // the same run
  EXPECT_EQ(thrown<SceneError>([&] { check_same_run("j.journal", {"x (1 in the file, 2 in the scene)"}, "s.toml"); }),
            "j.journal: --resume: made by another run than s.toml: x (1 in the file, 2 in the scene); use "
            "--overwrite to start again, or another --output");
}

TEST_F(OutputTargetTest, AFileTheDiskCannotHoldIsRefusedBeforeItIsMade) {
  const std::string p = path("map.h5");
  const OutputTarget target(p, {}, OutputLocking::none);
  const std::string e = thrown<IoError>([&] { target.check_space(1'000'000'000'000'000'000, "the map", "do less"); });
  EXPECT_EQ(e.rfind(p + ": the map needs 1e+09 GB, and its file system has ", 0), 0u) << e;
  EXPECT_TRUE(e.ends_with(" GB free; do less")) << e;
  EXPECT_EQ(thrown<IoError>([&] { target.check_space(1000, "the map", "do less"); }), "");
  EXPECT_FALSE(fs::exists(p));
}

TEST_F(OutputTargetTest, FilesBesideTheOutputAreCheckedForWhatIsThere) {
  const OutputTarget target(path("opt.h5"), {}, OutputLocking::none);
  fs::create_directory(path("opt_map.h5"));
  EXPECT_EQ(thrown<SceneError>([&] { target.check_beside(path("opt_map.h5"), "seeding map"); }),
            path("opt_map.h5") + ": seeding map: is a directory, not a regular file; name a new file");
  std::ofstream(path("opt_trajectory.h5")) << "x";
  EXPECT_EQ(thrown<SceneError>([&] { target.check_beside(path("opt_trajectory.h5"), "trajectory"); }), "");
}

}  // namespace
