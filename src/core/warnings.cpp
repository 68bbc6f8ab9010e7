#include "core/warnings.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"
#include "core/log.hpp"

namespace tw {

namespace {

bool same(const Warning& a, const Warning& b) {
  return a.code == b.code && a.subject == b.subject && a.fid == b.fid && a.message == b.message;
}

}  // namespace

std::string to_string(const Warning& warning) {
  std::string out;
  if (!warning.subject.empty()) out += warning.subject + ": ";
  if (warning.fid) out += fmt::format("FID {}: ", *warning.fid);
  out += warning.message;
  // One line whatever the message holds: a newline in a value (a key, a path) must not let a
  // warning forge another line.
  return single_line(out);
}

void fail_if_strict(const std::vector<Warning>& warnings, bool strict) {
  if (!strict || warnings.empty()) return;
  fail("strict: {} warning{} (first: {}); nothing written", warnings.size(),
       warnings.size() == 1 ? "" : "s", to_string(warnings.front()));
}

Warnings::Warnings(const Warnings& other) : list_(other.list()) {}

Warnings& Warnings::operator=(const Warnings& other) {
  if (this != &other) {
    std::vector<Warning> copy = other.list();
    const std::lock_guard lock(mutex_);
    list_ = std::move(copy);
  }
  return *this;
}

void Warnings::add(Warning warning) {
  {
    const std::lock_guard lock(mutex_);
    if (std::any_of(list_.begin(), list_.end(),
                    [&](const Warning& w) { return same(w, warning); })) {
      return;
    }
    list_.push_back(warning);
  }
  logger().warn("{}", to_string(warning));
}

void Warnings::add(std::string code, std::string subject, std::optional<std::int64_t> fid,
                   std::string message) {
  add(Warning{std::move(code), std::move(subject), fid, std::move(message)});
}

std::vector<Warning> Warnings::list() const {
  const std::lock_guard lock(mutex_);
  return list_;
}

std::size_t Warnings::size() const {
  const std::lock_guard lock(mutex_);
  return list_.size();
}

}  // namespace tw
