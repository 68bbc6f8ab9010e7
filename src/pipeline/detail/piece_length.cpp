#include "pipeline/detail/piece_length.hpp"

#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

namespace {
constexpr double kRibbonPieceLength = 4.0;  // metres: classes without synthesis
}  // namespace

double class_piece_length(const FeatureClassConfig& feature_class,
                          const std::vector<const SynthesisMethod*>& methods) {
  return class_ribbon_needs(feature_class, methods).piece_length.value_or(kRibbonPieceLength);
}

}  // namespace tw::detail
