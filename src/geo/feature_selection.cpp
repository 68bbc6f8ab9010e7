#include "geo/feature_selection.hpp"

#include <algorithm>

#include "geo/detail/vector_layer.hpp"

namespace tw {

std::vector<std::int64_t> selected_fids(const VectorSource& source) {
  detail::OpenVectorLayer opened = detail::open_vector_layer(source);
  std::vector<std::int64_t> fids;
  opened.layer->ResetReading();
  // Only the attributes are needed: no geometry is parsed.
  opened.layer->SetIgnoredFields(std::vector<const char*>{"OGR_GEOMETRY", nullptr}.data());
  while (OGRFeatureUniquePtr feature{opened.layer->GetNextFeature()})
    fids.push_back(std::int64_t(feature->GetFID()));
  std::sort(fids.begin(), fids.end());
  return fids;
}

}  // namespace tw
