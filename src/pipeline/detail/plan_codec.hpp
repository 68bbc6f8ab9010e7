#pragma once
// The value types of a WorldPlan as JSON values (stored as CBOR, RFC 8949, by plan_io): one
// list of fields per type, read and written by the same function, so the two directions cannot
// drift apart. Arrays of numbers (points, profiles, texels, heights) are CBOR byte strings of
// their little-endian bytes: exact (NaN included) and a fraction of the size of numbers.
#include <nlohmann/json.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.hpp"
#include "core/grid.hpp"
#include "core/vec2.hpp"

namespace tw::detail {

static_assert(std::endian::native == std::endian::little,
              "plan files hold little-endian numbers as they are in memory");

using nlohmann::json;

class JsonWriter;
class JsonReader;
class BinaryWriter;  // plan_binary.hpp
class BinaryReader;

template <class T>
concept Packed = std::is_arithmetic_v<T> || std::is_same_v<T, Vec2>;
// A vector of numbers: stored as one byte string.
template <class T>
concept PackedVector = requires(const T& v) {
  typename T::value_type;
  v.size();
  v.data();
}
&&Packed<typename T::value_type>;

// What the field lists are written against: `io(key, value)` writes or reads one field.
class JsonWriter {
 public:
  json value = json::object();
  template <class T>
  void operator()(const char* key, const T& v);
};

class JsonReader {
 public:
  JsonReader(const json& value, std::string path) : value_(value), path_(std::move(path)) {}
  template <class T>
  void operator()(const char* key, T& v);
  const std::string& path() const { return path_; }

 private:
  const json& value_;
  std::string path_;  // e.g. "patterns[3].ribbon", for messages
};

template <class T>
json encode(const T& v);
template <class T>
void decode(const json& j, T& v, const std::string& path);

// The field lists (plan_codec.cpp and, for templates, here). Each type used in a plan has one,
// read and written as JSON values and as bytes (plan_binary.hpp).
#define TW_PLAN_FIELDS(Type)              \
  void fields(JsonWriter& io, Type& v);   \
  void fields(JsonReader& io, Type& v);   \
  void fields(BinaryWriter& io, Type& v); \
  void fields(BinaryReader& io, Type& v)

// Defines the field list of Type for both directions and both forms (JSON, binary: the .cpp
// includes plan_binary.hpp), in one .cpp (plan_codec.cpp for the
// plan's own types, a method's file for its own): TW_DEFINE_PLAN_FIELDS(Type, TW_FIELD(a)
// TW_FIELD(b)). A field list is defined before the encode or decode that needs it.
#define TW_DEFINE_PLAN_FIELDS(Type, ...)   \
  template <class Io>                      \
  static void fields_of(Io& io, Type& v) { \
    __VA_ARGS__                            \
  }                                        \
  void fields(JsonWriter& io, Type& v) {   \
    fields_of(io, v);                      \
  }                                        \
  void fields(JsonReader& io, Type& v) {   \
    fields_of(io, v);                      \
  }                                        \
  void fields(BinaryWriter& io, Type& v) { \
    fields_of(io, v);                      \
  }                                        \
  void fields(BinaryReader& io, Type& v) { \
    fields_of(io, v);                      \
  }
#define TW_FIELD(name) io(#name, v.name);

template <class T>
concept HasFields = requires(JsonWriter& w, T& v) {
  fields(w, v);
};

template <class T>
json encode(const T& v) {
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_enum_v<T>) {
    return static_cast<std::int64_t>(v);
  } else if constexpr (std::is_arithmetic_v<T>) {
    return v;
  } else if constexpr (requires {
                         typename T::value_type;
                         v.has_value();
                       }) {  // optional
    return v ? encode(*v) : json();
  } else if constexpr (requires {
                         v.get();
                         typename T::element_type;
                       }) {  // shared_ptr
    return v ? encode(*v) : json();
  } else if constexpr (PackedVector<T>) {
    std::vector<std::uint8_t> bytes(v.size() * sizeof(typename T::value_type));
    if (!bytes.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
    return json::binary(std::move(bytes));
  } else if constexpr (requires {
                         typename T::value_type;
                         v.begin();
                       }) {  // vector, deque
    json array = json::array();
    for (const auto& item : v) array.push_back(encode(item));
    return array;
  } else {
    static_assert(HasFields<T>, "no field list for this type (plan_codec)");
    JsonWriter writer;
    fields(writer, const_cast<T&>(v));  // the writer only reads
    return std::move(writer.value);
  }
}

template <class T>
void decode(const json& j, T& v, const std::string& path) {
  const auto wrong = [&](const char* expected) {
    fail("{}: expected {}, got {}", path, expected, std::string(j.type_name()));
  };
  if constexpr (std::is_same_v<T, bool>) {
    if (!j.is_boolean()) wrong("a boolean");
    v = j.get<bool>();
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!j.is_string()) wrong("a string");
    v = j.get<std::string>();
  } else if constexpr (std::is_enum_v<T>) {
    if (!j.is_number_integer()) wrong("an integer");
    v = static_cast<T>(j.get<std::int64_t>());
  } else if constexpr (std::is_integral_v<T>) {
    if (!j.is_number_integer()) wrong("an integer");
    v = j.get<T>();
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!j.is_number()) wrong("a number");
    v = j.get<T>();
  } else if constexpr (requires {
                         typename T::value_type;
                         v.has_value();
                       }) {
    if (j.is_null()) {
      v.reset();
    } else {
      typename T::value_type inner{};
      decode(j, inner, path);
      v = std::move(inner);
    }
  } else if constexpr (requires {
                         v.get();
                         typename T::element_type;
                       }) {
    if (j.is_null()) {
      v.reset();
    } else {
      auto inner = std::make_shared<std::remove_const_t<typename T::element_type>>();
      decode(j, *inner, path);
      v = std::move(inner);
    }
  } else if constexpr (PackedVector<T>) {
    using Item = typename T::value_type;
    if (!j.is_binary()) wrong("a byte string");
    const auto& bytes = j.get_binary();
    if (bytes.size() % sizeof(Item) != 0)
      fail("{}: {} bytes is not a whole number of items", path, bytes.size());
    if constexpr (requires { v.resize(0); }) {
      v.resize(bytes.size() / sizeof(Item));
    } else if (bytes.size() != v.size() * sizeof(Item)) {  // std::array
      fail("{}: {} bytes, expected {}", path, bytes.size(), v.size() * sizeof(Item));
    }
    if (!bytes.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
  } else if constexpr (requires {
                         typename T::value_type;
                         v.begin();
                       }) {
    if (!j.is_array()) wrong("an array");
    v.clear();
    for (std::size_t i = 0; i < j.size(); ++i) {
      decode(j[i], v.emplace_back(), path + "[" + std::to_string(i) + "]");
    }
  } else {
    if (!j.is_object()) wrong("an object");
    JsonReader reader(j, path);
    fields(reader, v);
  }
}

template <class T>
void JsonWriter::operator()(const char* key, const T& v) {
  value[key] = encode(v);
}

template <class T>
void JsonReader::operator()(const char* key, T& v) {
  const std::string field = path_.empty() ? key : path_ + "." + key;
  const auto it = value_.find(key);
  if (it == value_.end()) fail("{}: missing", field);
  decode(*it, v, field);
}

template <class Io>
void raster_fields(Io& io, auto& raster) {
  io("width", raster.width);
  io("height", raster.height);
  io("pixels", raster.pixels);
}
template <class T>
void fields(JsonWriter& io, Raster<T>& v) {
  raster_fields(io, v);
}
template <class T>
void fields(JsonReader& io, Raster<T>& v) {
  raster_fields(io, v);
  if (v.pixels.size() != std::size_t(v.width) * std::size_t(v.height)) {
    fail("{}: {} pixels for {} x {}", io.path(), v.pixels.size(), v.width, v.height);
  }
}

TW_PLAN_FIELDS(GridSpec);
TW_PLAN_FIELDS(Window);

}  // namespace tw::detail
