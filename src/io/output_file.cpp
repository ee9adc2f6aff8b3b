#include "vibromap/io/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

namespace fs = std::filesystem;

std::string shown(const std::string& path) { return clip(path, 120); }

// `limit`: the longest file name allowed, bytes.
void check_name(const std::string& path, std::string_view option, std::size_t limit = kMaxOutputNameBytes) {
  if (path.empty()) throw SceneError(cat(option, ": empty; name the file to write"));
  const std::string base = fs::path(path).filename().string();
  if (base.empty() || base == "." || base == "..")
    throw SceneError(cat(shown(path), ": ", option, ": names a directory; name the file to write"));
  if (base.size() > limit)
    throw SceneError(cat(shown(path), ": ", option, ": the file name is ", std::to_string(base.size()),
                         " bytes long; at most ", std::to_string(limit),
                         " (the file system allows 255, and vibromap writes .lock, .journal and .tmp files beside it)"));
  if (path.size() > PATH_MAX - 64)
    throw SceneError(cat(shown(path), ": ", option, ": the path is ", std::to_string(path.size()), " bytes long; at most ",
                         std::to_string(PATH_MAX - 64)));
}

void check_directory(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) return;
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0)
    throw IoError(cat(shown(path), ": cannot write here: directory '", shown(dir.string()), "' does not exist"));
  if (!S_ISDIR(st.st_mode))
    throw IoError(cat(shown(path), ": cannot write here: '", shown(dir.string()), "' is not a directory"));
}

// lstat of `path`: false when nothing is there; throws IoError when it cannot be looked up.
bool look_up(const std::string& path, struct stat& st) {
  if (::lstat(path.c_str(), &st) == 0) return true;
  if (errno == ENOENT) return false;
  throw IoError(cat(shown(path), ": cannot look it up (", std::strerror(errno), ")"));
}

void refuse_non_regular(const std::string& path, std::string_view option, const struct stat& st) {
  if (S_ISREG(st.st_mode)) return;
  std::string what(file_kind(st.st_mode));
  if (S_ISLNK(st.st_mode)) {
    std::error_code ec;
    const fs::path to = fs::read_symlink(path, ec);
    if (!ec) what += cat(" (to '", shown(to.string()), "')");
    throw SceneError(cat(shown(path), ": ", option, ": is ", what,
                         "; vibromap never writes through a link: name the file itself, or a new one"));
  }
  throw SceneError(cat(shown(path), ": ", option, ": is ", what, ", not a regular file; name a new file"));
}

void sync_directory_of(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the rename itself has happened
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string_view file_kind(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

bool check_output(const std::string& path, const OutputPolicy& policy) {
  check_name(path, policy.option);
  check_directory(path);
  struct stat st {};
  if (!look_up(path, st)) return false;
  refuse_non_regular(path, policy.option, st);
  if (policy.resume || policy.overwrite) return true;
  throw SceneError(cat(shown(path), ": ", policy.option, ": already exists",
                       policy.exists.empty() ? std::string() : cat(" (", policy.exists, ")"), "; use ",
                       policy.resumable ? "--resume to continue it or " : "", "--overwrite to replace it"));
}

void check_opened_output(const std::string& path, int fd) {
  struct stat opened {}, named {};
  if (::fstat(fd, &opened) != 0 || ::lstat(path.c_str(), &named) != 0 || !S_ISREG(named.st_mode) ||
      opened.st_dev != named.st_dev || opened.st_ino != named.st_ino)
    throw SceneError(cat(shown(path), ": changed while it was being opened (it is no longer the regular file that was ",
                         "checked); run again"));
}

NewFile::NewFile(std::string target) : target_(std::move(target)) {
  check_name(target_, "output", NAME_MAX);
  check_directory(target_);
  struct stat st {};
  if (look_up(target_, st)) refuse_non_regular(target_, "output", st);
  // TARGET.XXXXXX.tmp (TARGET cut to fit NAME_MAX), made by mkostemps: O_CREAT | O_EXCL, so
  // never an existing file or link.
  constexpr std::string_view kSuffix = ".XXXXXX.tmp";
  const fs::path t(target_);
  const std::string base = t.filename().string().substr(0, NAME_MAX - kSuffix.size());
  std::string name = (t.parent_path() / base).string() + std::string(kSuffix);
  fd_ = ::mkostemps(name.data(), 4, O_CLOEXEC);
  if (fd_ < 0) throw IoError(cat(shown(target_), ": cannot create a new file beside it (", std::strerror(errno), ")"));
  path_ = std::move(name);
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd_, 0644 & ~mask);  // mkostemps makes it 0600; an output is readable like any other file
  struct stat made {};
  ::fstat(fd_, &made);
  dev_ = made.st_dev;
  ino_ = made.st_ino;
}

NewFile::NewFile(NewFile&& other) noexcept
    : target_(std::move(other.target_)), path_(std::move(other.path_)), fd_(other.fd_), dev_(other.dev_),
      ino_(other.ino_), committed_(other.committed_) {
  other.fd_ = -1;
  other.committed_ = true;  // nothing left to remove
}

NewFile::~NewFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !path_.empty()) ::unlink(path_.c_str());
}

void NewFile::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(cat(shown(target_), ": cannot write (", std::strerror(n < 0 ? errno : EIO), ")"));
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void NewFile::close_descriptor() {
  if (fd_ < 0) return;
  ::close(fd_);
  fd_ = -1;
}

void NewFile::check_same(int fd) const {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_dev != dev_ || st.st_ino != ino_)
    throw IoError(cat(shown(path_), ": the new file was replaced by another before it was written; run again"));
}

void NewFile::commit() {
  int fd = fd_;
  if (fd < 0) fd = ::open(path_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) throw IoError(cat(shown(path_), ": cannot open it to sync it (", std::strerror(errno), ")"));
  check_same(fd);
  const int rc = ::fsync(fd);
  const int err = errno;
  if (fd != fd_) ::close(fd);
  if (rc != 0 && err != EINVAL) throw IoError(cat(shown(target_), ": cannot sync it to disk (", std::strerror(err), ")"));
  struct stat st {};
  if (look_up(target_, st)) refuse_non_regular(target_, "output", st);
  if (std::rename(path_.c_str(), target_.c_str()) != 0)
    throw IoError(cat(shown(target_), ": cannot rename the new file '", shown(path_), "' to it (", std::strerror(errno),
                      ")"));
  committed_ = true;
  sync_directory_of(target_);
}

}  // namespace vibromap
