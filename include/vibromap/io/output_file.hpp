#pragma once
// How vibromap writes every output file: maps, trajectories, branches, basins, orbit diagrams,
// optimisations, CSV, journals and locks. One implementation, so that one rule holds for all:
//
// - An output is checked before any work (check_output): its name is not empty and fits the
//   file system with room for the files vibromap puts beside it (.lock, .journal, the
//   temporary file), its directory exists, and an existing output is a regular file that
//   --overwrite (or --resume) allows. A symbolic link, a directory, a device, a FIFO or a
//   socket is refused with one line (exit 2): vibromap never writes through a link. A user
//   who means the link's target names the target itself (e.g. -o "$(readlink -f LINK)").
// - A new output is written as a new file beside its target (NewFile: created exclusively, so
//   never an existing file or a link), synced to the disk and renamed over the target. An
//   existing target is never opened for writing nor truncated; a run deletes only the
//   temporary file it created itself.
// - A file opened again to be continued (--resume) is opened only when it is a regular file,
//   and checked to be the very file that was checked (check_opened_output).

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

namespace vibromap {

// The longest file name (bytes) vibromap accepts for an output: room is kept for the longest
// name it puts beside one (TARGET.journal, TARGET.XXXXXX.tmp) within the file system's 255.
inline constexpr std::size_t kMaxOutputNameBytes = 240;

// What an existing output may become.
struct OutputPolicy {
  std::string_view option = "--output";  // how the user named it, for messages, -
  bool overwrite = false;  // --overwrite: an existing regular file is replaced (never written in place), -
  bool resumable = false;  // the command has --resume: the "already exists" line offers it, -
  bool resume = false;     // --resume: an existing regular file is opened again to be continued, -
  std::string_view exists = {};  // what an existing file means, said when it is refused, -
};

// What a path that is not a regular file is ("a symbolic link", "a directory", "a FIFO (named
// pipe)", ...), for the one line that refuses it (outputs here, scenes in the scene reader).
std::string_view file_kind(mode_t mode);

// Checks `path` as an output before any work (see the header comment). Returns true when it
// exists (then it is a regular file that `policy` allows to replace or resume). Throws
// SceneError (exit 2) for a bad name, an existing output that is not a regular file, or one
// that may not be replaced; IoError (exit 4) for a missing directory or a failed look-up.
bool check_output(const std::string& path, const OutputPolicy& policy);

// After an existing output was opened (by path, e.g. by HDF5) on descriptor `fd`: throws
// SceneError unless `path` is still a regular file (not a link) and is the file `fd` has open.
void check_opened_output(const std::string& path, int fd);

// A new file beside `target`, named TARGET.XXXXXX.tmp and created exclusively (O_CREAT|O_EXCL:
// never an existing file, never through a link), mode 0644 (less the umask). Write it through
// descriptor() or by path() (HDF5: close_descriptor() first, then check_same(fd) once opened);
// commit() syncs it, renames it over the target and syncs the directory. Until then the target
// is untouched; the destructor removes the new file when it was not committed.
class NewFile {
 public:
  // Throws SceneError for a bad name or a target that may not be replaced by a new file (see
  // check_output), IoError when the file cannot be created.
  explicit NewFile(std::string target);
  ~NewFile();
  NewFile(NewFile&& other) noexcept;
  NewFile& operator=(NewFile&&) = delete;
  NewFile(const NewFile&) = delete;
  NewFile& operator=(const NewFile&) = delete;

  const std::string& path() const { return path_; }  // the new file (until commit)
  const std::string& target() const { return target_; }
  int descriptor() const { return fd_; }  // -1 after close_descriptor()

  void write(std::string_view bytes);  // appends at the descriptor; IoError when it fails
  void close_descriptor();             // the file stays (for writers that open path() themselves)
  // Throws IoError unless `fd` (opened by path() by another library) is the file created here.
  void check_same(int fd) const;
  // Syncs the file to the disk, renames it over the target and syncs the directory. An
  // existing target must still be a regular file. The descriptor, if open, stays open (on the
  // target now). Throws IoError (the new file is then removed, the target untouched).
  void commit();
  // After commit(): the open descriptor (of the target now), the caller's to close.
  int release_descriptor() { return std::exchange(fd_, -1); }

 private:
  std::string target_;
  std::string path_;
  int fd_ = -1;
  dev_t dev_ = 0;
  ino_t ino_ = 0;
  bool committed_ = false;
};

}  // namespace vibromap
