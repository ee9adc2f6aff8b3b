#include "vibromap/io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "vibromap/core/text.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/scene/scene.hpp"

namespace vibromap {
namespace {

std::string holder_text() {
  char host[256] = "unknown";
  ::gethostname(host, sizeof host - 1);
  char when[64] = "";
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  return cat("pid ", std::to_string(::getpid()), " on host ", host, ", since ", when);
}

std::string read_holder(int fd) {
  char buf[512];
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string text(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.empty() ? "another process" : clip(text, 200);
}

bool same_file(int fd, const std::string& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

}  // namespace

OutputLock::OutputLock(const std::string& output) : path_(output + ".lock") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(output).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw IoError(cat(output, ": cannot write here: directory '", dir.string(), "' does not exist"));
  for (;;) {
    // Never through a link, never blocking on a FIFO; anything but a regular file is refused.
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
    if (fd < 0 && errno == ELOOP)
      throw SceneError(cat(path_, ": is a symbolic link; vibromap never writes through a link: remove it"));
    if (fd < 0) throw IoError(cat(output, ": cannot write here: cannot create ", path_, " (", std::strerror(errno), ")"));
    if (struct stat st {}; ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      throw SceneError(cat(path_, ": is not a regular file; vibromap keeps its lock there: remove it"));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      if (err == EWOULDBLOCK) {
        const std::string holder = read_holder(fd);
        ::close(fd);
        throw SceneError(cat(output, ": another vibromap run is writing it (", holder,
                             "); wait for it to end, or write to another --output"));
      }
      ::close(fd);
      ::unlink(path_.c_str());
      std::cerr << "vibromap: note: " << output << ": the file system does not lock files (" << std::strerror(err)
                << "); make sure no other run writes it\n";
      return;
    }
    if (!same_file(fd, path_)) {  // the previous holder removed it between our open and our lock
      ::close(fd);
      continue;
    }
    const std::string holder = holder_text() + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, holder.data(), holder.size(), 0) < 0) {
      const int err = errno;
      ::close(fd);
      ::unlink(path_.c_str());
      throw IoError(cat(output, ": cannot write ", path_, " (", std::strerror(err), ")"));
    }
    fd_ = fd;
    return;
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still holding it: a waiting run then finds the file gone and retries
  ::close(fd_);
}

}  // namespace vibromap
