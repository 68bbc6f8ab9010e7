// Fuzz target: a plan object's bytes (CBOR, docs/distributed.md) decoded as the plan's report,
// its terrain parameters and its lines, the way load_plan decodes verified objects. A bad object is
// a tw::Error or a json::exception (which load_plan turns into an error naming the plan and key);
// anything else that escapes, a crash or a sanitizer report is a finding.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.hpp"
#include "pipeline/detail/plan_fields.hpp"

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

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
