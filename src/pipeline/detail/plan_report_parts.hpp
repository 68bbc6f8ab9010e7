#pragma once
// A method's report part (RunReport::method_parts) in the plan folder, the one way every method
// stores it (SynthesisMethod::encode_report, decode_report): the part's fields as bytes
// (plan_binary.hpp) in one binary object, refused on decoding with a message naming
// plan.json and `methods.<method>.report`.
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "pipeline/detail/plan_binary.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/method_plan.hpp"

namespace tw::detail {

template <class Part>
nlohmann::json put_report_part(const MethodPayload& part, const PlanObjects& objects) {
  return objects.put_binary(to_bytes(dynamic_cast<const Part&>(part)));
}

template <class Part>
std::unique_ptr<MethodPayload> get_report_part(const nlohmann::json& entry,
                                               const PlanObjects& objects,
                                               std::string_view method) {
  const std::string key = "methods." + std::string(method) + ".report";
  auto part = std::make_unique<Part>();
  from_bytes(objects.get_binary(entry, key).body(), *part,
             "plan " + (objects.dir() / "plan.json").string() + ": " + key);
  return part;
}

}  // namespace tw::detail
