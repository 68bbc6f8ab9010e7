#pragma once
// A synthesis method's part of a WorldPlan (pipeline/synthesis_method.hpp, docs/methods.md):
// what the method decided, as a type of the method's own behind MethodPayload, and the output
// windows of its items, binned. The plan holds one entry per method, in the methods' order, and
// knows nothing of what is inside.
#include <memory>
#include <string>
#include <vector>

#include "core/clone_ptr.hpp"
#include "raster/window_index.hpp"

namespace tw {

class SynthesisMethod;

// What one method planned. Each method derives its own (MethodPayloadOf does the copying).
struct MethodPayload {
  virtual ~MethodPayload() = default;
  virtual std::unique_ptr<MethodPayload> clone() const = 0;
};

template <class Derived>
using MethodPayloadOf = Cloneable<MethodPayload, Derived>;

// One method's entry in the plan: a value type (copying a plan copies its payloads).
struct MethodPlan {
  const SynthesisMethod* method = nullptr;
  ClonePtr<MethodPayload> payload;
  // The windows of its items (SynthesisMethod::windows), binned by index_plan.
  WindowIndex index;
};

// The method's name (its entry in plan.json); "" without a method.
std::string method_name(const MethodPlan& entry);

[[noreturn]] void fail_payload_type(const MethodPlan& entry);

// The entry's payload as the method's own type. Throws tw::Error naming the method when it is
// another type (an entry handed to the wrong method).
template <class T>
T& payload_as(MethodPlan& entry) {
  T* p = dynamic_cast<T*>(entry.payload.get());
  if (!p) fail_payload_type(entry);
  return *p;
}
template <class T>
const T& payload_as(const MethodPlan& entry) {
  const T* p = dynamic_cast<const T*>(entry.payload.get());
  if (!p) fail_payload_type(entry);
  return *p;
}

}  // namespace tw
