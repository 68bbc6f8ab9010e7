#include "pipeline/detail/conformance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrain/conform.hpp"

namespace tw::detail {

std::vector<std::vector<LineMove>> conform_lines(const TerrainOptions& terrain,
                                                 const HeightfieldSource& heightfield,
                                                 std::vector<std::vector<LineFeature>>& lines,
                                                 Warnings& warnings) {
  std::vector<std::vector<LineMove>> moves(lines.size());
  const double half_cell =
      0.5 * std::min(heightfield.grid().pixel_width, heightfield.grid().pixel_height);
  HeightSampler heights(heightfield);
  for (std::size_t c = 0; c < lines.size(); ++c) {
    const TerrainClass& feature_class = terrain.classes[c];
    moves[c].resize(lines[c].size());
    if (feature_class.conform_corridor <= 0.0) continue;
    const bool ridge = feature_class.kind == FeatureKind::ridge;
    const ConformOptions options{feature_class.conform_corridor,
                                 ridge ? ConformTarget::crest : ConformTarget::valley_floor};
    const std::string subject = "features." + feature_class.name;
    std::vector<Curve> drawn, conformed;
    std::vector<double> tolerance;
    for (const LineFeature& line : lines[c]) {
      drawn.push_back(Curve{line.points, line.closed});
      tolerance.push_back(0.5 * line.width + half_cell);  // as terrain's end contacts
    }
    conformed = drawn;
    std::vector<ConformResult> results;
    for (std::size_t i = 0; i < lines[c].size(); ++i) {
      results.push_back(conform_line(heights, drawn[i], options));
      if (results.back().conformed) conformed[i] = results.back().line;
    }
    reattach_ends(drawn, conformed, tolerance);
    for (std::size_t i = 0; i < lines[c].size(); ++i) {
      LineFeature& line = lines[c][i];
      const ConformResult& r = results[i];
      line.points = conformed[i].points;  // a line kept as drawn may still be reattached
      if (!r.conformed) {
        warnings.add("not_conformed", subject, line.fid,
                     fmt::format("kept as drawn: {}", r.kept_because));
        continue;
      }
      moves[c][i] = {r.max_move, r.mean_move};
      if (r.max_move > half_cell) {
        // Two distances, so the message never reads as a move beyond the corridor: how far
        // the new line lies from the drawn one (bounded by the corridor), and how far apart
        // the two lines are anywhere (larger where the path cuts across a drawn bend).
        warnings.add("conformed", subject, line.fid,
                     fmt::format("moved onto the {} (corridor {:g} m): the new line lies at "
                                 "most {:.1f} m from the drawn one (mean {:.1f} m); the lines "
                                 "are up to {:.1f} m apart where it cuts across a drawn bend",
                                 ridge ? "crest" : "valley floor", options.corridor, r.max_offset,
                                 r.mean_move, r.max_move));
      }
    }
  }
  return moves;
}

namespace {

void warn_limit(Warnings& warnings, const std::string& subject, std::int64_t fid, const char* code,
                const char* held, double bound, const ProfileLimit& limit,
                const std::string& advice) {
  if (limit.length <= 0.0) return;
  warnings.add(code, subject, fid,
               fmt::format("{} at most {:g} m {} the terrain over {:.0f} m of the line; worst at "
                           "{:.0f} m along (x {:.1f}, y {:.1f}), {:.1f} m beyond the bound{}",
                           held, bound, code[0] == 'f' ? "above" : "below", limit.length,
                           limit.along, limit.at.x, limit.at.y, limit.excess, advice));
}

// What to do about a river held by max_carve: a line that misses the DEM's valley (a coarse map
// crossing spurs) is answered by conformance; a depression the line really crosses (a DEM's
// pit, even under a line traced from the DEM) by a larger max_carve, if a cut is wanted.
std::string carve_advice(const TerrainClass& feature_class) {
  if (feature_class.conform_corridor <= 0.0) {
    return fmt::format(
        ". The river meets the terrain there (a spur, or the rim of a closed depression of the "
        "DEM): if the line misses the DEM's valley, add `conform: {{ corridor: <metres> }}` to "
        "{} (about the map's positional accuracy, e.g. 250 for 1:250 000 data) to move it "
        "onto the valley floor; to cut deeper instead, raise profile.max_carve "
        "(docs/terrain.md, Conformance)",
        "features." + feature_class.name);
  }
  return fmt::format(
      ". The valley lies beyond the {:g} m corridor here: widen conform.corridor, or raise "
      "profile.max_carve to allow a deeper cut",
      feature_class.conform_corridor);
}

}  // namespace

namespace {

// The largest |rise| / run between neighbouring profile samples (0 without a profile).
double steepest_grade(const std::vector<float>& profile, double step) {
  double grade = 0.0;
  if (step <= 0.0) return grade;
  for (std::size_t i = 1; i < profile.size(); ++i)
    grade = std::max(grade, std::abs(double(profile[i]) - profile[i - 1]) / step);
  return grade;
}

}  // namespace

void report_earthwork(const TerrainOptions& terrain,
                      const std::vector<std::vector<LineFeature>>& lines, const TerrainPlan& plan,
                      RunReport& report, Warnings& warnings) {
  // terrain_features lists the lines class by class: flat index -> (class, line).
  std::vector<std::pair<std::size_t, std::size_t>> owner;
  for (std::size_t c = 0; c < lines.size(); ++c)
    for (std::size_t i = 0; i < lines[c].size(); ++i) owner.emplace_back(c, i);
  for (std::size_t k = 0; k < plan.features.size(); ++k) {
    const auto [c, i] = owner.at(plan.input_index[k]);
    const FeatureEarthwork& e = plan.earthwork[k];
    FeatureReport& feature = report.classes[c].features[i];
    feature.cut_max_m = e.max_cut;
    feature.fill_max_m = e.max_fill;
    feature.grade_max = steepest_grade(plan.profiles[k], plan.steps[k]);
    const TerrainClass& feature_class = terrain.classes[c];
    const std::string subject = "features." + feature_class.name;
    const std::int64_t fid = lines[c][i].fid;
    if (feature_class.kind == FeatureKind::river) {
      warn_limit(warnings, subject, fid, "carve_limited", "bed held",
                 max_carve(feature_class.river), e.cut_limited, carve_advice(feature_class));
    } else if (feature_class.kind == FeatureKind::road) {
      warn_limit(warnings, subject, fid, "cut_limited", "cut held",
                 feature_class.road.max_cut.value_or(0.0), e.cut_limited, "");
      warn_limit(warnings, subject, fid, "fill_limited", "fill held",
                 feature_class.road.max_fill.value_or(0.0), e.fill_limited, "");
    }
  }
}

}  // namespace tw::detail
