#pragma once
// An append-only journal of campaign results (GNU parallel's joblog idea): what is recorded as
// done is never redone. The multistart campaign keeps its finished starts in one, so a killed
// optimisation resumes where it stopped.
//
// Layout: a header (magic "VMJ1", format version (u32: kJournalFormat, io/file_format.hpp), the
// run's identity text, CRC-32), then one record per result: item (u64), length (u64), the
// result's bytes, CRC-32 of the three. Records are appended through a buffer and reach the disk
// at sync() (write + fsync). A process killed mid-write leaves at most a torn last record: open()
// keeps every intact record, drops a torn tail and says how many bytes it dropped; a damaged
// record in the middle is refused (IoError), since what follows it cannot be trusted; a journal
// of another format version is refused (FileVersionError) before its records are read.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vibromap {

class Journal {
 public:
  struct Record {
    std::uint64_t item = 0;
    std::vector<char> bytes;
  };

  // Creates `path` (a new file renamed over it: see io/output_file.hpp) with `identity` in its
  // header, synced. Throws IoError (SceneError when `path` is a link or not a regular file).
  static Journal create(const std::string& path, std::string_view identity);
  // Opens an existing journal for appending: reads its identity and records. Throws
  // FileVersionError for a journal of another format version, IoError naming the path when it
  // cannot be read or is damaged before its tail.
  static Journal open(const std::string& path);

  Journal(Journal&&) noexcept;
  Journal& operator=(Journal&&) noexcept;
  ~Journal();

  const std::string& path() const { return path_; }
  const std::string& identity() const { return identity_; }
  const std::vector<Record>& records() const { return records_; }  // read by open()
  std::size_t dropped_bytes() const { return dropped_; }           // a torn tail cut off by open()

  void append(std::uint64_t item, const char* bytes, std::size_t size);  // buffered
  void sync();  // writes the buffer and fsyncs; throws IoError

 private:
  Journal() = default;
  std::string path_;
  std::string identity_;
  std::vector<Record> records_;
  std::size_t dropped_ = 0;
  std::vector<char> buffer_;
  int fd_ = -1;
};

// CRC-32 (IEEE 802.3, as zlib's crc32) of `size` bytes, continuing from `crc`.
std::uint32_t crc32(const char* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace vibromap
