#pragma once
// Warnings are first-class (docs/pipeline.md, "Warnings"): each names what it is about (a key
// such as `features.rivers`, and the FID when a feature is concerned), a stable code and one
// line of reason. A run collects them in one Warnings value that it passes to the stages that
// can warn (no global state), logs each once, lists them in report.json and, under `--strict`,
// fails before anything is written.
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace tw {

struct Warning {
  std::string code;                 // stable, machine-readable: "empty_class", "repaired", ...
  std::string subject;              // the key it is about: "features.rivers", "existing.0", ...
  std::optional<std::int64_t> fid;  // the feature, when one is concerned
  std::string message;              // one line, no trailing period
};

// "features.rivers: FID 2: message" (the subject and FID parts only when present).
std::string to_string(const Warning& warning);

// Collects warnings from any thread. The first time a warning is added it is logged at warn
// level; an identical one (same code, subject, FID and message) is neither logged nor kept
// again, so a stage that runs twice over the same feature warns once.
class Warnings {
 public:
  Warnings() = default;
  Warnings(const Warnings& other);
  Warnings& operator=(const Warnings& other);

  void add(Warning warning);
  void add(std::string code, std::string subject, std::optional<std::int64_t> fid,
           std::string message);
  // In the order they were first added.
  std::vector<Warning> list() const;
  std::size_t size() const;
  bool empty() const { return size() == 0; }

 private:
  mutable std::mutex mutex_;
  std::vector<Warning> list_;
};

// Under strict (--strict, `strict: true`), any warning is an error, raised before anything is
// written: "strict: N warnings (first: <warning>); nothing written". Every command calls it
// before it stages its outputs.
void fail_if_strict(const std::vector<Warning>& warnings, bool strict);

}  // namespace tw
