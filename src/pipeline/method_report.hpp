#pragma once
// A synthesis method's part of a run's report (pipeline/synthesis_method.hpp, docs/methods.md):
// what the method reports of its classes, features and the run, as a type of the method's own
// behind MethodPayload, as a plan holds its entry. RunReport holds one part per method that
// reports, and knows nothing of what is inside; the method writes it into report.json
// (SynthesisMethod::report_json) and into the plan folder (encode_report, decode_report).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/method_plan.hpp"

namespace tw {

// One method's part: a value type (copying a report copies its parts).
struct MethodReportPart {
  std::string method;  // its method's name()
  ClonePtr<MethodPayload> part;
};

// The part of type T (a method's own) among a report's `method_parts`; null when none.
template <class T, class Report>
const T* method_report(const Report& report) {
  for (const MethodReportPart& p : report.method_parts)
    if (const T* typed = dynamic_cast<const T*>(p.part.get())) return typed;
  return nullptr;
}
template <class T, class Report>
T* method_report(Report& report) {
  for (MethodReportPart& p : report.method_parts)
    if (T* typed = dynamic_cast<T*>(p.part.get())) return typed;
  return nullptr;
}

// The part of type T of `method`, added (empty) when the report has none yet.
template <class T, class Report>
T& method_report(Report& report, const std::string& method) {
  if (T* found = method_report<T>(report)) return *found;
  auto part = std::make_unique<T>();
  T& typed = *part;
  report.method_parts.emplace_back(method, std::move(part));
  return typed;
}

}  // namespace tw
