#pragma once
// The placements of a synthesis as JSON (schema in docs/synthesis.md): enough to render again
// without re-running the DP (the paper: "the output of the synthesizer is a set of texture
// coordinates").
#include <string>
#include <string_view>

#include "synth/synthesize.hpp"

namespace tw {

void save_placements(const Synthesis& synthesis, const std::string& exemplar_path,
                     const std::string& path);
// Throws tw::Error naming the file and the key on malformed input.
Synthesis load_placements(const std::string& path, std::string* exemplar_path = nullptr);

// The same document as text (the cache keeps it inside its entries); `path` names the source in
// messages.
std::string placements_to_json(const Synthesis& synthesis, const std::string& exemplar_path);
Synthesis placements_from_json(std::string_view text, const std::string& path,
                               std::string* exemplar_path = nullptr);

}  // namespace tw
