#pragma once
// The value types of a WorldPlan as bytes (the plan folder's objects/<hash>.bin, plan_io): the
// same field lists as the JSON form (plan_codec.hpp), written in order without their names, so
// a reader builds the values directly, with no document in between (issue #23 item 4: decoding
// the world's ribbons through a JSON tree was half of a render-tile).
//   bool, enum, number   its bytes, little-endian (an enum as int64, a bool as one byte)
//   string              uint64 length, then the bytes
//   optional, pointer   one byte (0 absent, 1 present), then the value
//   vector of numbers   uint64 count, then the items' bytes (Vec2: x, y)
//   other container     uint64 count, then each item
//   struct              its fields in the order of its field list
// The object's header (magic, plan version) and its hash are the plan folder's (plan_objects).
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "pipeline/detail/plan_codec.hpp"

namespace tw::detail {

class BinaryWriter {
 public:
  std::string bytes;

  template <class T>
  void operator()(const char* /*key*/, const T& v) {
    write(v);
  }
  template <class T>
  void write(const T& v);
  void raw(const void* data, std::size_t size) {
    bytes.append(static_cast<const char*>(data), size);
  }
  void count(std::size_t n) {
    const std::uint64_t n64 = n;
    raw(&n64, sizeof n64);
  }
};

class BinaryReader {
 public:
  // `where` names the object in messages (e.g. "plan DIR: ribbons").
  BinaryReader(std::string_view bytes, std::string where)
      : begin_(bytes.data()),
        pos_(bytes.data()),
        end_(bytes.data() + bytes.size()),
        where_(std::move(where)) {}

  template <class T>
  void operator()(const char* /*key*/, T& v) {
    read(v);
  }
  template <class T>
  void read(T& v);
  void raw(void* out, std::size_t size) {
    if (size > std::size_t(end_ - pos_))
      fail("{}: {} bytes wanted at byte {} of {} (truncated, or written by another version)",
           where_, size, pos_ - begin_, end_ - begin_);
    if (size) std::memcpy(out, pos_, size);
    pos_ += size;
  }
  // A count of items of `item_size` bytes at least each, refused when the rest cannot hold them
  // (a corrupt count never allocates).
  std::size_t count(std::size_t item_size) {
    std::uint64_t n = 0;
    raw(&n, sizeof n);
    if (item_size && n > std::uint64_t(end_ - pos_) / item_size)
      fail("{}: {} items at byte {} of {}: more than the object holds", where_, n,
           pos_ - begin_ - 8, end_ - begin_);
    return std::size_t(n);
  }
  std::size_t offset() const { return std::size_t(pos_ - begin_); }
  std::size_t size() const { return std::size_t(end_ - begin_); }
  void seek(std::size_t offset) {
    if (offset > size()) fail("{}: offset {} past its {} bytes", where_, offset, size());
    pos_ = begin_ + offset;
  }
  // Throws unless every byte was read.
  void finish() const {
    if (pos_ != end_)
      fail("{}: {} bytes left over after its values (written by another version?)", where_,
           end_ - pos_);
  }
  const std::string& path() const { return where_; }

 private:
  const char* begin_;
  const char* pos_;
  const char* end_;
  std::string where_;
};

template <class T>
void BinaryWriter::write(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    const std::uint8_t b = v ? 1 : 0;
    raw(&b, 1);
  } else if constexpr (std::is_same_v<T, std::string>) {
    count(v.size());
    raw(v.data(), v.size());
  } else if constexpr (std::is_enum_v<T>) {
    const auto e = static_cast<std::int64_t>(v);
    raw(&e, sizeof e);
  } else if constexpr (std::is_arithmetic_v<T>) {
    raw(&v, sizeof v);
  } else if constexpr (requires {
                         typename T::value_type;
                         v.has_value();
                       }) {  // optional
    write(bool(v));
    if (v) write(*v);
  } else if constexpr (requires {
                         v.get();
                         typename T::element_type;
                       }) {  // shared_ptr
    write(bool(v));
    if (v) write(*v);
  } else if constexpr (PackedVector<T>) {
    count(v.size());
    raw(v.data(), v.size() * sizeof(typename T::value_type));
  } else if constexpr (requires {
                         typename T::value_type;
                         v.begin();
                       }) {  // vector, deque
    count(v.size());
    for (const auto& item : v) write(static_cast<const typename T::value_type&>(item));
  } else {
    static_assert(HasFields<T>, "no field list for this type (plan_codec)");
    fields(*this, const_cast<T&>(v));  // the writer only reads
  }
}

template <class T>
void BinaryReader::read(T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    std::uint8_t b = 0;
    raw(&b, 1);
    if (b > 1) fail("{}: byte {} is not a boolean", where_, offset() - 1);
    v = b == 1;
  } else if constexpr (std::is_same_v<T, std::string>) {
    v.resize(count(1));
    raw(v.data(), v.size());
  } else if constexpr (std::is_enum_v<T>) {
    std::int64_t e = 0;
    raw(&e, sizeof e);
    v = static_cast<T>(e);
  } else if constexpr (std::is_arithmetic_v<T>) {
    raw(&v, sizeof v);
  } else if constexpr (requires {
                         typename T::value_type;
                         v.has_value();
                       }) {
    bool present = false;
    read(present);
    if (!present) {
      v.reset();
    } else {
      typename T::value_type inner{};
      read(inner);
      v = std::move(inner);
    }
  } else if constexpr (requires {
                         v.get();
                         typename T::element_type;
                       }) {
    bool present = false;
    read(present);
    if (!present) {
      v.reset();
    } else {
      auto inner = std::make_shared<std::remove_const_t<typename T::element_type>>();
      read(*inner);
      v = std::move(inner);
    }
  } else if constexpr (PackedVector<T>) {
    using Item = typename T::value_type;
    const std::size_t n = count(sizeof(Item));
    if constexpr (requires { v.resize(0); }) {
      v.resize(n);
    } else if (n != v.size()) {  // std::array
      fail("{}: {} items at byte {}, expected {}", where_, n, offset() - 8, v.size());
    }
    raw(v.data(), n * sizeof(Item));
  } else if constexpr (requires {
                         typename T::value_type;
                         v.begin();
                       }) {
    const std::size_t n = count(1);
    v.clear();
    for (std::size_t i = 0; i < n; ++i) {
      typename T::value_type item{};
      read(item);
      v.push_back(std::move(item));
    }
  } else {
    fields(*this, v);
  }
}

template <class T>
void fields(BinaryWriter& io, Raster<T>& v) {
  raster_fields(io, v);
}
template <class T>
void fields(BinaryReader& io, Raster<T>& v) {
  raster_fields(io, v);
  if (v.pixels.size() != std::size_t(v.width) * std::size_t(v.height)) {
    fail("{}: {} pixels for {} x {}", io.path(), v.pixels.size(), v.width, v.height);
  }
}

// A value as bytes and back (the whole object: bytes left over are an error).
template <class T>
std::string to_bytes(const T& v) {
  BinaryWriter writer;
  writer.write(v);
  return std::move(writer.bytes);
}
template <class T>
void from_bytes(std::string_view bytes, T& v, const std::string& where) {
  BinaryReader reader(bytes, where);
  reader.read(v);
  reader.finish();
}

}  // namespace tw::detail
