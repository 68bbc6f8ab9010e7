#include "pipeline/detail/ribbon_cache.hpp"

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_stage_cache.hpp"
#include "ribbon/junction_search.hpp"

namespace tw::detail {

TW_PLAN_FIELDS(JunctionMember);
TW_PLAN_FIELDS(Junction);
TW_PLAN_FIELDS(Extent);
TW_PLAN_FIELDS(JunctionSearch);
TW_DEFINE_PLAN_FIELDS(JunctionMember, TW_FIELD(curve) TW_FIELD(arc_length) TW_FIELD(at_endpoint))
TW_DEFINE_PLAN_FIELDS(Junction, TW_FIELD(position) TW_FIELD(members) TW_FIELD(crossing))
TW_DEFINE_PLAN_FIELDS(Extent, TW_FIELD(min) TW_FIELD(max))
TW_DEFINE_PLAN_FIELDS(JunctionSearch,
                      TW_FIELD(tolerance_m) TW_FIELD(junctions) TW_FIELD(extents) TW_FIELD(boxes))

namespace fs = std::filesystem;

RibbonCache::RibbonCache(const fs::path& dir, Warnings& warnings)
    : dir_(dir), warnings_(warnings), folder_(dir, warnings) {}

RibbonSteps RibbonCache::steps() {
  RibbonSteps steps;
  steps.ribbon = [this](const Curve& centerline, const RibbonParams& params) {
    return ribbon(centerline, params);
  };
  steps.junctions = [this](const std::vector<Curve>& curves, double tolerance_m) {
    return junctions(curves, tolerance_m);
  };
  return steps;
}

Ribbon RibbonCache::ribbon(const Curve& centerline, const RibbonParams& params) {
  const std::string key = plan_stage_hasher("ribbon")
                              .points(centerline.points)
                              .boolean(centerline.closed)
                              .real(params.width)
                              .real(params.delta)
                              .real(params.tangent_window)
                              .digest()
                              .hex();
  const fs::path path = dir_ / "plan" / "ribbon" / (key + ".twc");
  if (std::optional<Ribbon> found = read_plan_value<Ribbon>(path, key, "ribbon", warnings_))
    return std::move(*found);
  Ribbon made = make_ribbon(centerline, params);
  ++ribbons_made_;
  folder_.write(path, {{"key", key}, {"value", to_bytes(made)}});
  return made;
}

std::vector<Junction> RibbonCache::junctions(const std::vector<Curve>& curves, double tolerance_m) {
  const std::string key = plan_stage_hasher("junctions").real(tolerance_m).digest().hex();
  std::vector<std::string> hashes;
  for (const Curve& curve : curves)
    hashes.push_back(Hasher().points(curve.points).boolean(curve.closed).digest().hex());
  const fs::path path = dir_ / "plan" / "junctions" / (key + ".twc");
  CacheRead read = read_cache_entry(path);
  JunctionSearch latest;
  std::vector<std::string> latest_hashes;
  if (read.state == CacheRead::State::ok) {
    try {
      if (read.sections["key"] != key) fail("key mismatch");
      from_bytes(read.sections["curves"], latest_hashes, path.string());
      from_bytes(read.sections["value"], latest, path.string());
      if (latest_hashes.size() != latest.boxes.size())
        fail("{} curves, {} boxes", latest_hashes.size(), latest.boxes.size());
    } catch (const Error& e) {
      read.state = CacheRead::State::corrupt;
      read.problem = e.what();
    }
  }
  if (read.state == CacheRead::State::corrupt)
    warn_corrupt_plan_entry(warnings_, "junctions", path, read.problem);
  if (read.state == CacheRead::State::ok && latest_hashes == hashes) {
    touch_cache_entry(path);
    return std::move(latest.junctions);
  }
  JunctionSearch search;
  if (read.state == CacheRead::State::ok && latest_hashes.size() == hashes.size()) {
    std::vector<bool> changed;
    for (std::size_t i = 0; i < hashes.size(); ++i)
      changed.push_back(hashes[i] != latest_hashes[i]);
    search = update_junctions(latest, curves, changed);
  } else {
    search = search_junctions(curves, tolerance_m);
  }
  curves_searched_ += search.curves_searched;
  folder_.write(path, {{"key", key}, {"curves", to_bytes(hashes)}, {"value", to_bytes(search)}});
  return std::move(search.junctions);
}

}  // namespace tw::detail
