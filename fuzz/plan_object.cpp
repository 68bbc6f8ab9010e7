// Fuzz target: a plan object's bytes (docs/distributed.md) decoded as the plan's report, its
// terrain parameters, its lines, its ribbons and the patterns method's patterns and exemplars, the
// way load_plan decodes verified objects: as a binary object's body
// (pipeline/detail/plan_binary.hpp) and as CBOR (the other methods' entries). A bad object is a
// tw::Error or a json::exception (which load_plan turns into an error naming the plan and key);
// anything else that escapes, a crash or a sanitizer report is a finding.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_ribbons.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"

namespace {

template <class T>
void decode_as(const nlohmann::json& object) {
  T value;
  try {
    tw::detail::decode(object, value, "fuzz");
  } catch (const tw::Error&) {
  } catch (const nlohmann::json::exception&) {
  }
}

template <class T>
void from_bytes_as(std::string_view bytes) {
  T value;
  try {
    tw::detail::from_bytes(bytes, value, "fuzz");
  } catch (const tw::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  from_bytes_as<tw::RunReport>(bytes);
  from_bytes_as<decltype(tw::WorldPlan::terrain_params)>(bytes);
  from_bytes_as<decltype(tw::WorldPlan::lines)>(bytes);
  try {
    std::vector<std::vector<tw::Ribbon>> ribbons;
    tw::detail::ribbons_from_bytes(bytes, ribbons, nullptr, "fuzz");
  } catch (const tw::Error&) {
  }
  try {  // the patterns method's objects (pattern_method.hpp)
    tw::detail::PlannedPattern pattern;
    tw::detail::pattern_from_bytes(bytes, pattern, "fuzz");
  } catch (const tw::Error&) {
  }
  try {
    tw::Exemplar exemplar;
    tw::detail::exemplar_from_bytes(bytes, exemplar, "fuzz");
  } catch (const tw::Error&) {
  }
  nlohmann::json object;
  try {
    object = nlohmann::json::from_cbor(std::vector<std::uint8_t>(data, data + size));
  } catch (const nlohmann::json::exception&) {
    return 0;  // not CBOR: load_plan's "files.KEY: not CBOR"
  }
  decode_as<tw::RunReport>(object);
  decode_as<decltype(tw::WorldPlan::terrain_params)>(object);
  decode_as<decltype(tw::WorldPlan::lines)>(object);
  return 0;
}
