// libFuzzer target: tw::load_placements on an arbitrary file. What it accepts must survive
// save_placements and load again unchanged: the file is "enough to render again", so a value
// the loader lets through but the writer cannot represent is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "synth/placements_io.hpp"

namespace {

std::string scratch_path(const char* role) {
  return (std::filesystem::temp_directory_path() /
          ("terraweave-fuzz-placements-" + std::to_string(::getpid()) + "-" + role + ".json"))
      .string();
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same(const tw::Synthesis& a, const tw::Synthesis& b) {
  if (a.column != b.column || a.closed != b.closed || a.backend != b.backend ||
      a.total_cost != b.total_cost || !same_bits(a.mean_seam_cost, b.mean_seam_cost) ||
      !same_bits(a.mean_seam_cost_stitched, b.mean_seam_cost_stitched) ||
      a.valid_counts != b.valid_counts || a.placements.size() != b.placements.size())
    return false;
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    const tw::Placement& p = a.placements[i];
    const tw::Placement& q = b.placements[i];
    if (p.ux != q.ux || p.uy != q.uy || p.empty != q.empty || !same_bits(p.scale, q.scale) ||
        !same_bits(p.origin.x, q.origin.x) || !same_bits(p.origin.y, q.origin.y) ||
        !same_bits(p.along.x, q.along.x) || !same_bits(p.along.y, q.along.y) ||
        !same_bits(p.across.x, q.across.x) || !same_bits(p.across.y, q.across.y) ||
        p.stitch != q.stitch)
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string input_path = scratch_path("in");
  static const std::string again_path = scratch_path("again");
  {
    std::ofstream file(input_path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  tw::Synthesis loaded;
  std::string exemplar;
  try {
    loaded = tw::load_placements(input_path, &exemplar);
  } catch (const tw::Error&) {
    return 0;  // refused with a message: the expected answer to a bad file
  }
  tw::save_placements(loaded, exemplar, again_path);
  std::string exemplar_again;
  tw::Synthesis again;
  try {
    again = tw::load_placements(again_path, &exemplar_again);
  } catch (const tw::Error& e) {
    std::fprintf(stderr, "fuzz: %s\n", e.what());
    tw::fuzz::broken_promise("save_placements wrote what load_placements refuses");
  }
  if (exemplar_again != exemplar || !same(loaded, again))
    tw::fuzz::broken_promise("placements changed through save and load");
  return 0;
}
