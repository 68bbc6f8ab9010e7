#include "synth/synthesize.hpp"

#include "synth/detail/backend_factory.hpp"

namespace tw {

Synthesis synthesize(const Exemplar& exemplar, const Ribbon& ribbon, const GridSpec& canvas,
                     const SparseRaster<std::uint8_t>* forbidden, const SynthParams& params,
                     OpenCLContext* context) {
  auto backend = detail::make_backend(params.backend, context);
  return detail::synthesize_on(*backend, exemplar, ribbon, canvas, forbidden, params);
}

}  // namespace tw
