#pragma once
// The forms, defaults and choices the key table is written with (detail/pipeline_keys.hpp),
// shared by the table and the methods' parts of it (detail/method_keys.hpp), so every part reads
// like the docs' key tables.
#include <limits>
#include <string_view>
#include <vector>

#include "pipeline/detail/pipeline_keys.hpp"

namespace tw::detail::key_forms {

inline ValueForm number(double lo = -std::numeric_limits<double>::infinity(),
                        double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::number, .minimum = lo, .maximum = hi};
}
inline ValueForm positive(double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::number, .minimum = 0.0, .maximum = hi, .exclusive_minimum = true};
}
inline ValueForm non_negative(double hi = std::numeric_limits<double>::infinity()) {
  return number(0.0, hi);
}
inline ValueForm integer(double lo, double hi = std::numeric_limits<double>::infinity()) {
  return {.type = ValueType::integer, .minimum = lo, .maximum = hi};
}
inline ValueForm uint64() {
  return integer(0.0);
}
inline ValueForm boolean() {
  return {.type = ValueType::boolean};
}
inline ValueForm string() {
  return {.type = ValueType::string};
}
inline ValueForm path() {
  return {.type = ValueType::path};
}
inline ValueForm choice(std::vector<std::string_view> values) {
  return {.type = ValueType::choice, .values = std::move(values)};
}
inline ValueForm block(std::string_view name) {
  return {.type = ValueType::block, .block = name};
}
inline ValueForm of(ValueType type) {
  return {.type = type};
}

inline KeyDefault no_default() {
  return {};
}
inline KeyDefault def(double value) {
  return {.kind = KeyDefault::Kind::number, .number = value};
}
inline KeyDefault def_bool(bool value) {
  return {.kind = KeyDefault::Kind::boolean, .boolean = value};
}
inline KeyDefault def_text(std::string_view text) {
  return {.kind = KeyDefault::Kind::text, .text = text};
}

inline constexpr bool required = true;

inline const std::vector<std::string_view> kBackends{"cpu", "opencl", "auto"};

}  // namespace tw::detail::key_forms
