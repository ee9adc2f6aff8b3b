#pragma once
// The farm's byte codec: results and work travel between ranks, and into checkpoint journals,
// as flat little-endian byte strings. A campaign's codec writes its Result with ByteWriter and
// reads it back with ByteReader, field by field in a fixed order (never a struct's raw bytes,
// whose padding is undefined), and names its layout with a version number.

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace vibromap {

static_assert(std::endian::native == std::endian::little, "the wire format is little-endian");

// A truncated or malformed byte string (a bug, or a damaged journal).
class WireError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ByteWriter {
 public:
  template <class T>
    requires std::is_arithmetic_v<T>
  void put(T v) {  // resize and copy: GCC 12 warns -Wstringop-overflow (falsely) on an insert here
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &v, sizeof(T));
  }
  void put(std::string_view s) {
    put(static_cast<std::uint64_t>(s.size()));
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void put(const std::vector<double>& v) {
    put(static_cast<std::uint64_t>(v.size()));
    const auto* p = reinterpret_cast<const char*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(double));
  }
  void put_bytes(const char* data, std::size_t n) { bytes_.insert(bytes_.end(), data, data + n); }

  std::vector<char>& bytes() { return bytes_; }
  const std::vector<char>& bytes() const { return bytes_; }
  std::size_t size() const { return bytes_.size(); }
  void clear() { bytes_.clear(); }

 private:
  std::vector<char> bytes_;
};

class ByteReader {
 public:
  ByteReader(const char* data, std::size_t size) : data_(data), size_(size) {}
  explicit ByteReader(const std::vector<char>& bytes) : ByteReader(bytes.data(), bytes.size()) {}

  template <class T>
    requires std::is_arithmetic_v<T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string get_string() {
    const std::size_t n = count(1);
    std::string s(data_ + pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<double> get_doubles() {
    const std::size_t n = count(sizeof(double));
    std::vector<double> v(n);
    if (n > 0) std::memcpy(v.data(), data_ + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return v;
  }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }
  const char* here() const { return data_ + pos_; }

 private:
  void need(std::size_t n) const {
    if (n > size_ - pos_) throw WireError("truncated message: needs " + std::to_string(n) + " more bytes, has " +
                                          std::to_string(size_ - pos_));
  }
  // A length prefix, checked against what is left (a damaged length never allocates).
  std::size_t count(std::size_t element) {
    const auto n = get<std::uint64_t>();
    if (n > (size_ - pos_) / element) throw WireError("malformed message: a length of " + std::to_string(n) +
                                                      " exceeds the bytes left");
    return static_cast<std::size_t>(n);
  }
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace vibromap
