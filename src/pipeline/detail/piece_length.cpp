#include "pipeline/detail/piece_length.hpp"

#include "core/error.hpp"

namespace tw::detail {

namespace {
constexpr double kRibbonPieceLength = 4.0;  // metres: classes without synthesis
}  // namespace

double class_piece_length(const FeatureClassConfig& feature_class) {
  if (!feature_class.synthesis) return kRibbonPieceLength;
  if (!feature_class.synthesis->delta)
    fail("features.{}.synthesis: delta not resolved (with_method_defaults)", feature_class.name);
  return *feature_class.synthesis->delta;
}

}  // namespace tw::detail
