// The one way vibromap writes an output (io/output_file.hpp): checked names and kinds, a new
// file created exclusively beside the target, renamed over it only on commit, removed otherwise.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/file_format.hpp"
#include "vibromap/io/journal.hpp"
#include "vibromap/io/output_file.hpp"
#include "vibromap/io/scene/scene.hpp"
#include "support/thrown.hpp"

namespace fs = std::filesystem;
using namespace vibromap;
using vibromap::test::thrown;

namespace {

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vibromap_output_file_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
  }
  static void write(const std::string& p, const std::string& text) { std::ofstream(p) << text; }
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }

  fs::path dir_;
};

TEST_F(OutputFile, CommitReplacesTheTargetByRenameAndLeavesNothingElse) {
  const std::string target = path("out.csv");
  write(target, "old\n");
  fs::create_hard_link(target, path("twin.csv"));  // shares the old file's inode
  {
    NewFile f(target);
    EXPECT_NE(f.path(), target);
    EXPECT_EQ(f.path().rfind(target + ".", 0), 0u);  // beside it: TARGET.XXXXXX.tmp
    f.write("new\n");
    EXPECT_EQ(read(target), "old\n");  // untouched until commit
    f.commit();
  }
  EXPECT_EQ(read(target), "new\n");
  EXPECT_EQ(read(path("twin.csv")), "old\n");  // the old file was not written in place
  EXPECT_EQ(entries(), 2u);
  struct stat st {};
  ASSERT_EQ(::stat(target.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u & ~static_cast<unsigned>([] { const mode_t m = ::umask(0); ::umask(m); return m; }()));
}

TEST_F(OutputFile, WithoutCommitTheNewFileIsRemovedAndTheTargetKept) {
  const std::string target = path("out.csv");
  write(target, "old\n");
  {
    NewFile f(target);
    f.write("half");
  }
  EXPECT_EQ(read(target), "old\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFile, LinksDirectoriesAndFifosAreRefusedAndUntouched) {
  write(path("canary"), "keep\n");
  fs::create_symlink(path("canary"), path("link"));
  fs::create_symlink(path("nowhere"), path("dangling"));
  fs::create_directory(path("dir"));
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  for (const auto& [name, kind] : {std::pair{"link", "a symbolic link"}, std::pair{"dangling", "a symbolic link"},
                                   std::pair{"dir", "a directory"}, std::pair{"fifo", "a FIFO"}}) {
    const std::string p = path(name);
    EXPECT_NE(thrown<SceneError>([&] { check_output(p, {.overwrite = true}); }).find(std::string("is ") + kind),
              std::string::npos) << name;
    EXPECT_NE(thrown<SceneError>([&] { NewFile f(p); }).find(std::string("is ") + kind), std::string::npos) << name;
    EXPECT_NE(thrown<SceneError>([&] { write_hdf5_atomically(p, [](Hdf5File&) {}); }), "") << name;
  }
  EXPECT_EQ(read(path("canary")), "keep\n");
  EXPECT_FALSE(fs::exists(path("nowhere")));  // a dangling link is not followed to create its target
  EXPECT_EQ(entries(), 5u);  // canary, link, dangling, dir, fifo: nothing was made beside them
}

TEST_F(OutputFile, AnExistingFileNeedsOverwriteOrResume) {
  const std::string p = path("map.h5");
  EXPECT_FALSE(check_output(p, {}));  // nothing there: fine, and says so
  write(p, "x");
  EXPECT_EQ(thrown<SceneError>([&] { check_output(p, {}); }),
            p + ": --output: already exists; use --overwrite to replace it");
  EXPECT_EQ(thrown<SceneError>([&] { check_output(p, {.option = "-o", .resumable = true}); }),
            p + ": -o: already exists; use --resume to continue it or --overwrite to replace it");
  EXPECT_EQ(thrown<SceneError>([&] { check_output(p, {.option = "journal", .exists = "a run left it"}); }),
            p + ": journal: already exists (a run left it); use --overwrite to replace it");
  EXPECT_TRUE(check_output(p, {.overwrite = true}));
  EXPECT_TRUE(check_output(p, {.resume = true}));
}

TEST_F(OutputFile, BadNamesAndMissingDirectoriesAreOneLine) {
  EXPECT_EQ(thrown<SceneError>([&] { check_output("", {}); }), "--output: empty; name the file to write");
  EXPECT_NE(thrown<SceneError>([&] { check_output(path(std::string(241, 'x')), {}); })
                .find("the file name is 241 bytes long; at most 240"),
            std::string::npos);
  EXPECT_EQ(thrown<SceneError>([&] { check_output(path(std::string(240, 'x')), {}); }), "");
  EXPECT_EQ(thrown<IoError>([&] { check_output(path("no_such_dir/m.h5"), {}); }),
            path("no_such_dir/m.h5") + ": cannot write here: directory '" + path("no_such_dir") + "' does not exist");
  EXPECT_NE(thrown<SceneError>([&] { check_output(path("dir/."), {}); }).find("names a directory"), std::string::npos);
}

TEST_F(OutputFile, TheLongestAllowedNameStillHasRoomForItsNewFile) {
  const std::string target = path(std::string(kMaxOutputNameBytes, 'y'));
  NewFile f(target);
  f.write("ok\n");
  f.commit();
  EXPECT_EQ(read(target), "ok\n");
}

TEST_F(OutputFile, AnHdf5FileIsWrittenBesideAndRenamedAndAFailureLeavesTheOldOne) {
  const std::string p = path("t.h5");
  write(p, "old\n");
  EXPECT_THROW(write_hdf5_atomically(p, [](Hdf5File&) { throw IoError("disk full, say"); }), IoError);
  EXPECT_EQ(read(p), "old\n");
  EXPECT_EQ(entries(), 1u);
  write_hdf5_atomically(p, [](Hdf5File& f) { f.set_attribute("answer", std::int64_t{42}); });
  EXPECT_EQ(Hdf5File(p).read_int_attribute("answer"), 42);
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFile, AnOpenedFileMustBeTheOneChecked) {
  const std::string p = path("map.h5");
  write(p, "a");
  write(path("other"), "b");
  const int fd = ::open(path("other").c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  EXPECT_NE(thrown<SceneError>([&] { check_opened_output(p, fd); }).find("changed while it was being opened"),
            std::string::npos);
  ::close(fd);
  const int same = ::open(p.c_str(), O_RDONLY);
  EXPECT_EQ(thrown<SceneError>([&] { check_opened_output(p, same); }), "");
  ::close(same);
}

TEST_F(OutputFile, AJournalIsCreatedAsANewFileAndNeverOpenedThroughALink) {
  const std::string p = path("o.h5.journal");
  write(path("canary"), "keep\n");
  fs::create_symlink(path("canary"), p);
  EXPECT_NE(thrown<SceneError>([&] { Journal::create(p, "id"); }).find("is a symbolic link"), std::string::npos);
  EXPECT_THROW(Journal::open(p), IoError);
  EXPECT_EQ(read(path("canary")), "keep\n");
  fs::remove(p);
  {
    Journal j = Journal::create(p, "identity");
    const char rec[] = "abc";
    j.append(7, rec, 3);
    j.sync();
  }
  const Journal again = Journal::open(p);
  EXPECT_EQ(again.identity(), "identity");
  ASSERT_EQ(again.records().size(), 1u);
  EXPECT_EQ(again.records()[0].item, 7u);
}

TEST_F(OutputFile, AJournalOfAnotherFormatVersionIsRefusedNamingBothVersions) {
  const std::string p = path("o.h5.journal");
  Journal::create(p, "identity");
  std::string bytes = read(p);
  ASSERT_EQ(bytes.substr(0, 4), "VMJ1");
  ASSERT_EQ(bytes[4], static_cast<char>(kJournalFormat.version));  // the version: 4 bytes, little-endian
  bytes[4] = 2;
  write(p, bytes);
  EXPECT_EQ(thrown<FileVersionError>([&] { Journal::open(p); }),
            p + ": an optimisation journal of format version 2; this vibromap reads version 3 only: make the file "
                "again with this vibromap");
}

}  // namespace
