#pragma once
// A synthesis method's options in the config (docs/methods.md, "Its reading"), kept opaquely as
// the plan keeps the method's entry (pipeline/method_plan.hpp): the config's own
// (PipelineConfig::methods: the areas' classes) and a line class's (FeatureClassConfig::methods:
// its `synthesis:`, `grow:` or `network:` block). Each is a type of the method's own, which
// MethodOptionsOf copies; the config and its classes name no method's field.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/clone_ptr.hpp"

namespace tw {

struct MethodOptions {
  virtual ~MethodOptions() = default;
  virtual std::unique_ptr<MethodOptions> clone() const = 0;
};

template <class Derived>
using MethodOptionsOf = Cloneable<MethodOptions, Derived>;

// One method's options: a value type (copying a config copies them).
struct MethodConfigPart {
  std::string method;  // the method's name (SynthesisMethod::name())
  ClonePtr<MethodOptions> options;
};

// The options of method `method` among `parts` as its own type T; null when there are none (or,
// for a method that names another's type, of another type).
template <class T>
const T* find_method_options(const std::vector<MethodConfigPart>& parts,
                             const std::string& method) {
  for (const MethodConfigPart& part : parts)
    if (part.method == method) return dynamic_cast<const T*>(part.options.get());
  return nullptr;
}

template <class T>
T* find_method_options(std::vector<MethodConfigPart>& parts, const std::string& method) {
  for (MethodConfigPart& part : parts)
    if (part.method == method) return dynamic_cast<T*>(part.options.get());
  return nullptr;
}

// The same, added (default T) when missing: a method's reader fills its options with it.
template <class T>
T& method_options_in(std::vector<MethodConfigPart>& parts, const std::string& method) {
  for (MethodConfigPart& part : parts)
    if (T* found = part.method == method ? dynamic_cast<T*>(part.options.get()) : nullptr)
      return *found;
  parts.emplace_back(method, std::make_unique<T>());
  return static_cast<T&>(*parts.back().options);
}

// Removes the options of method `method` from `parts` (none: nothing happens).
inline void drop_method_options(std::vector<MethodConfigPart>& parts, const std::string& method) {
  std::erase_if(parts, [&](const MethodConfigPart& part) { return part.method == method; });
}

}  // namespace tw
