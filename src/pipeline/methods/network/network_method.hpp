#pragma once
// Curve networks by example as a synthesis method (pipeline/synthesis_method.hpp): a class with
// `network` gets its lines grown as a network (network_classes.hpp), once, in the plan;
// its lines are the class's features and its report the class's `network`, so its entry holds
// nothing else.
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/method_keys.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

const SynthesisMethod& network_method();
// Its keys of a pipeline file (detail/method_keys.hpp).
MethodKeys network_keys();
// Its reading of them (detail/method_config.hpp; network_config.cpp).
MethodReader network_reader();

}  // namespace tw::detail
