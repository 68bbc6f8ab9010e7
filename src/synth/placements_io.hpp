#pragma once
// The placements of a synthesis as JSON (schema in docs/synthesis.md): enough to render again
// without re-running the DP (the paper: "the output of the synthesizer is a set of texture
// coordinates").
#include <string>

#include "synth/synthesize.hpp"

namespace tw {

void save_placements(const Synthesis& synthesis, const std::string& exemplar_path,
                     const std::string& path);
// Throws tw::Error naming the file and the key on malformed input.
Synthesis load_placements(const std::string& path, std::string* exemplar_path = nullptr);

}  // namespace tw
