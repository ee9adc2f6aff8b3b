#include "vibromap/io/journal.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <utility>

#include "vibromap/core/text.hpp"
#include "vibromap/io/file_format.hpp"
#include "vibromap/io/hdf5_file.hpp"
#include "vibromap/io/output_file.hpp"

namespace vibromap {
namespace {

constexpr char kMagic[4] = {'V', 'M', 'J', '1'};
constexpr auto kFormat = static_cast<std::uint32_t>(kJournalFormat.version);  // in the header, 4 bytes

std::array<std::uint32_t, 256> crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}

[[noreturn]] void io_fail(const std::string& path, std::string_view what) {
  throw IoError(cat(path, ": ", what, errno ? cat(" (", std::strerror(errno), ")") : std::string()));
}

template <class T>
void append_value(std::vector<char>& out, T v) {
  const auto* p = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), p, p + sizeof v);
}

template <class T>
bool read_value(const std::vector<char>& in, std::size_t& pos, T& v) {
  if (in.size() - pos < sizeof v) return false;
  std::memcpy(&v, in.data() + pos, sizeof v);
  pos += sizeof v;
  return true;
}

std::vector<char> read_all(const std::string& path, int fd) {
  std::vector<char> data;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) io_fail(path, "cannot read the journal");
    if (n == 0) return data;
    data.insert(data.end(), buf, buf + n);
  }
}

std::vector<char> header(std::string_view identity) {
  std::vector<char> h(kMagic, kMagic + 4);
  append_value(h, kFormat);
  append_value(h, static_cast<std::uint64_t>(identity.size()));
  h.insert(h.end(), identity.begin(), identity.end());
  append_value(h, crc32(h.data(), h.size()));
  return h;
}

void write_fully(const std::string& path, int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      io_fail(path, "cannot write the journal");
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

}  // namespace

std::uint32_t crc32(const char* data, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = crc_table();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ static_cast<unsigned char>(data[i])) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

Journal Journal::create(const std::string& path, std::string_view identity) {
  Journal j;
  j.path_ = path;
  j.identity_ = std::string(identity);
  // A new file with the header, synced and renamed over `path` (never a write through a link
  // or into an existing file); its descriptor then appends to the journal at `path`.
  NewFile out(path);
  const std::vector<char> h = header(identity);
  out.write(std::string_view(h.data(), h.size()));
  out.commit();
  j.fd_ = out.release_descriptor();
  return j;
}

Journal Journal::open(const std::string& path) {
  Journal j;
  j.path_ = path;
  errno = 0;
  j.fd_ = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (j.fd_ < 0) io_fail(path, "cannot open the journal");
  struct stat st {};
  if (::fstat(j.fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    errno = 0;
    io_fail(path, "the journal is not a regular file");
  }
  const std::vector<char> data = read_all(path, j.fd_);
  errno = 0;
  std::size_t pos = 4;
  std::uint32_t format = 0, crc = 0;
  std::uint64_t length = 0;
  if (data.size() < 4 || std::memcmp(data.data(), kMagic, 4) != 0) io_fail(path, "not a vibromap journal");
  if (!read_value(data, pos, format)) io_fail(path, "the journal's header is damaged");
  check_version(path, kJournalFormat, format);
  if (!read_value(data, pos, length) || length > data.size() - pos) io_fail(path, "the journal's header is damaged");
  j.identity_.assign(data.data() + pos, static_cast<std::size_t>(length));
  pos += static_cast<std::size_t>(length);
  const std::size_t header_end = pos;
  if (!read_value(data, pos, crc) || crc != crc32(data.data(), header_end)) io_fail(path, "the journal's header is damaged");
  std::size_t good = pos;
  while (pos < data.size()) {
    std::uint64_t item = 0, size = 0;
    const std::size_t start = pos;
    if (!read_value(data, pos, item) || !read_value(data, pos, size) || size > data.size() - pos) break;
    Record r{item, std::vector<char>(data.begin() + static_cast<long>(pos), data.begin() + static_cast<long>(pos + size))};
    pos += static_cast<std::size_t>(size);
    if (!read_value(data, pos, crc)) break;
    if (crc != crc32(data.data() + start, pos - sizeof crc - start)) {
      if (pos < data.size()) io_fail(path, cat("the journal is damaged at byte ", std::to_string(start)));
      break;  // a torn last record
    }
    j.records_.push_back(std::move(r));
    good = pos;
  }
  j.dropped_ = data.size() - good;
  if (j.dropped_ > 0 && ::ftruncate(j.fd_, static_cast<off_t>(good)) != 0) io_fail(path, "cannot cut the journal's torn tail");
  if (::lseek(j.fd_, 0, SEEK_END) < 0) io_fail(path, "cannot seek in the journal");
  return j;
}

Journal::Journal(Journal&& o) noexcept
    : path_(std::move(o.path_)), identity_(std::move(o.identity_)), records_(std::move(o.records_)),
      dropped_(o.dropped_), buffer_(std::move(o.buffer_)), fd_(std::exchange(o.fd_, -1)) {}

Journal& Journal::operator=(Journal&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_);
    identity_ = std::move(o.identity_);
    records_ = std::move(o.records_);
    dropped_ = o.dropped_;
    buffer_ = std::move(o.buffer_);
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(std::uint64_t item, const char* bytes, std::size_t size) {
  const std::size_t start = buffer_.size();
  append_value(buffer_, item);
  append_value(buffer_, static_cast<std::uint64_t>(size));
  buffer_.insert(buffer_.end(), bytes, bytes + size);
  append_value(buffer_, crc32(buffer_.data() + start, buffer_.size() - start));
}

void Journal::sync() {
  errno = 0;
  write_fully(path_, fd_, buffer_.data(), buffer_.size());
  buffer_.clear();
  if (::fsync(fd_) != 0) io_fail(path_, "cannot sync the journal to disk");
}

}  // namespace vibromap
