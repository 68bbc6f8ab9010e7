#pragma once
// `terraweave exemplar inspect IMG`: what an exemplar implies for its synthesis
// (synth/exemplar_stats.hpp), as text or JSON, with an optional preview PNG.
#include <filesystem>
#include <string>

namespace tw {

struct ExemplarInspectCommand {
  std::filesystem::path exemplar;
  std::filesystem::path preview;  // optional PNG: band, centre, period ticks, column coverage
  bool json = false;
  bool continuous_alpha = false;
  bool allow_network = false;
};

// The report (text lines, or one JSON object); throws tw::Error naming the file at fault.
std::string run_exemplar_inspect(const ExemplarInspectCommand& command);

}  // namespace tw
