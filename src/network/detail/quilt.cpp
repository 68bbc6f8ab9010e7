#include "network/detail/quilt.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>

#include "core/boost_geometry.hpp"
#include "network/detail/box_clip.hpp"

namespace tw::network_detail {

namespace {

using namespace geometry;
using SegValue = std::pair<BgSegment, int>;  // a segment and its line (or block)
using Segments = bgi::rtree<SegValue, bgi::quadratic<16>>;
using EndValue = std::pair<BgPoint, int>;

// A block's side as a fraction of the exemplar's shorter side, and the overlap compared between
// neighbouring blocks as a fraction of the block.
constexpr double kBlockFraction = 0.6;
constexpr double kOverlapFraction = 0.18;
// Seam ends are joined when their lines cross the seam within this angle of each other.
constexpr double kStitchCos = 0.64;  // cos 50°
// A part of a line with both ends on seams, shorter than this fraction of the stitch radius, is
// a sliver.
constexpr double kSliverFraction = 1.0;
// The candidates best on the seam among which the edges' traits choose.
constexpr int kShortlist = 16;
// The weight of the bearing histograms' cumulative distance in QuiltTraits::mismatch (its 12 bins
// sum to several times an L1's size; 0.2 met the most targets over seeds 1-9 of 0.2, 0.25, 0.3,
// 0.5 and 1, and 3 more than the L1: the counties' bearings 0.061 -> 0.046 at seed 1).
constexpr double kBearingCdfWeight = 0.2;

double nearest(const Segments& index, Vec2 p, double cap) {
  std::vector<SegValue> hit;
  index.query(bgi::nearest(to_bg(p), 1), std::back_inserter(hit));
  return hit.empty() ? cap : std::min(cap, bg::distance(hit[0].first, to_bg(p)));
}

void insert_line(Segments& index, const std::vector<Vec2>& pts, int id) {
  for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    if (!(pts[k] == pts[k + 1])) index.insert({BgSegment(to_bg(pts[k]), to_bg(pts[k + 1])), id});
}

// The vertex next to an end of a polyline, and the end itself.
Vec2& end_vertex(std::vector<Vec2>& pts, int end) {
  return end == 0 ? pts.front() : pts.back();
}
Vec2 inner_vertex(const std::vector<Vec2>& pts, int end) {
  return end == 0 ? pts[1] : pts[pts.size() - 2];
}

// Where p lies along `line` (arc length to its nearest point).
double arc_position(const std::vector<Vec2>& line, Vec2 p) {
  double best = INFINITY, at = 0.0, walked = 0.0;
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec2 d = line[k + 1] - line[k];
    const double size = length(d);
    const double t = size > 0.0 ? std::clamp(dot(p - line[k], d) / (size * size), 0.0, 1.0) : 0.0;
    const double gap = distance(p, line[k] + t * d);
    if (gap < best) best = gap, at = walked + t * size;
    walked += size;
  }
  return at;
}

// The exemplar line `line` beyond a cut at p, away from the part's vertex `inner`, for `reach`
// metres: it runs on straight past the line's own end (a junction whose other lines the block
// did not bring).
std::vector<Vec2> continuation_of(const std::vector<Vec2>& line, Vec2 p, Vec2 inner, double reach) {
  std::vector<Vec2> path{p};
  if (!(reach > 0.0) || line.size() < 2) return path;
  std::vector<Vec2> ahead = line;
  if (arc_position(line, inner) > arc_position(line, p)) std::reverse(ahead.begin(), ahead.end());
  const double from = arc_position(ahead, p);
  double walked = 0.0, left = reach;
  for (std::size_t k = 0; k + 1 < ahead.size() && left > 0.0; ++k) {
    const double size = distance(ahead[k], ahead[k + 1]);
    walked += size;
    if (walked <= from + 1e-9 * reach) continue;
    const double step = distance(path.back(), ahead[k + 1]);
    if (step >= left) {
      path.push_back(lerp(path.back(), ahead[k + 1], left / step));
      return path;
    }
    path.push_back(ahead[k + 1]);
    left -= step;
  }
  if (path.size() < 2)
    path.push_back(p + normalized(p - inner) * left);
  else if (left > 0.0)
    path.push_back(path.back() + normalized(path.back() - path[path.size() - 2]) * left);
  return path;
}

// The distance to the exemplar's nearest line on a lattice over its extent, clamped, read
// bilinearly: the candidates' scores read it hundreds of times per block (an R-tree query each
// would dominate the synthesis).
class DistanceField {
 public:
  DistanceField(const Segments& lines, Vec2 lo, Vec2 hi, double cell, double clamp)
      : lo_(lo), clamp_(clamp) {
    cell_ = std::max({cell, (hi.x - lo.x) / 1024.0, (hi.y - lo.y) / 1024.0, 1e-9});
    width_ = int(std::ceil((hi.x - lo.x) / cell_)) + 1;
    height_ = int(std::ceil((hi.y - lo.y) / cell_)) + 1;
    d_.resize(std::size_t(width_) * std::size_t(height_));
    for (int j = 0; j < height_; ++j)
      for (int i = 0; i < width_; ++i)
        d_[std::size_t(j) * std::size_t(width_) + std::size_t(i)] =
            nearest(lines, lo + cell_ * Vec2{double(i), double(j)}, clamp);
  }
  // The clamped distance at p; beyond the lattice, the clamp (no exemplar there).
  double at(Vec2 p) const {
    const double x = (p.x - lo_.x) / cell_, y = (p.y - lo_.y) / cell_;
    if (!(x >= 0.0 && y >= 0.0 && x <= width_ - 1 && y <= height_ - 1)) return clamp_;
    const int i = std::min(width_ - 2, int(x)), j = std::min(height_ - 2, int(y));
    const double u = x - i, v = y - j;
    const auto d = [&](int a, int b) {
      return d_[std::size_t(b) * std::size_t(width_) + std::size_t(a)];
    };
    return (1 - v) * ((1 - u) * d(i, j) + u * d(i + 1, j)) +
           v * ((1 - u) * d(i, j + 1) + u * d(i + 1, j + 1));
  }

 private:
  Vec2 lo_;
  double clamp_, cell_ = 1.0;
  int width_ = 2, height_ = 2;
  std::vector<double> d_;
};

// Histograms of the exemplar's edges' bearing, curvature and length (the last two in bins of
// its own quantiles), and of the edges the quilt's blocks have brought so far.
class QuiltTraits {
 public:
  static constexpr int kBins = 12;
  explicit QuiltTraits(const Network& exemplar) {
    std::vector<double> curvature, size;
    for (const NetworkEdge& e : exemplar.edges) {
      curvature.push_back(curvature_of(e.points));
      size.push_back(polyline_length(e.points));
    }
    const std::vector<double> curvature_edges = quantile_edges(curvature);
    const std::vector<double> length_edges = quantile_edges(size);
    for (std::size_t e = 0; e < exemplar.edges.size(); ++e) {
      const auto& pts = exemplar.edges[e].points;
      bins_.push_back({bearing_of(pts.back() - pts.front()), bin(curvature_edges, curvature[e]),
                       bin(length_edges, size[e])});
      for (int t = 0; t < 3; ++t)
        want_[std::size_t(t)][std::size_t(bins_.back()[std::size_t(t)])] += 1.0;
    }
    for (auto& h : want_)
      for (double& v : h) v /= std::max<double>(1.0, double(exemplar.edges.size()));
  }
  // The sum over the three traits of the distance between the exemplar's histogram and the
  // placed edges' with `edges` added: L1 for curvature and length, the cumulative one for bearing.
  double mismatch(const std::vector<int>& edges) const {
    auto have = have_;
    for (int e : edges)
      for (int t = 0; t < 3; ++t)
        have[std::size_t(t)][std::size_t(bins_[std::size_t(e)][std::size_t(t)])] += 1.0;
    const double total = count_ + double(edges.size());
    if (!(total > 0.0)) return 0.0;
    double m = 0.0;
    for (int t = 1; t < 3; ++t)
      for (int k = 0; k < kBins; ++k)
        m += std::abs(have[std::size_t(t)][std::size_t(k)] / total -
                      want_[std::size_t(t)][std::size_t(k)]);
    // Bearings by their cumulative distribution (a binned W1, as the statistics compare them): an
    // L1 over bins does not see a block shifting the output's bearings into the next bin.
    double have_below = 0.0, want_below = 0.0;
    for (int k = 0; k < kBins; ++k) {
      have_below += have[0][std::size_t(k)] / total;
      want_below += want_[0][std::size_t(k)];
      m += kBearingCdfWeight * std::abs(have_below - want_below);
    }
    return m;
  }
  void add(const std::vector<int>& edges) {
    for (int e : edges)
      for (int t = 0; t < 3; ++t)
        have_[std::size_t(t)][std::size_t(bins_[std::size_t(e)][std::size_t(t)])] += 1.0;
    count_ += double(edges.size());
  }

 private:
  static double curvature_of(const std::vector<Vec2>& pts) {
    double turning = 0.0;
    for (std::size_t k = 1; k + 1 < pts.size(); ++k) {
      const Vec2 a = pts[k] - pts[k - 1], b = pts[k + 1] - pts[k];
      turning += std::abs(std::atan2(cross(a, b), dot(a, b)));
    }
    const double size = polyline_length(pts);
    return size > 0.0 ? turning / size : 0.0;
  }
  static int bearing_of(Vec2 chord) {
    const double b =
        std::fmod(std::atan2(chord.x, chord.y) * 180.0 / std::numbers::pi + 360.0, 180.0);
    return std::min(kBins - 1, int(b / (180.0 / kBins)));
  }
  static std::vector<double> quantile_edges(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::vector<double> edges;
    for (int k = 1; k < kBins && !v.empty(); ++k)
      edges.push_back(v[v.size() * std::size_t(k) / kBins]);
    return edges;
  }
  static int bin(const std::vector<double>& edges, double v) {
    return int(std::upper_bound(edges.begin(), edges.end(), v) - edges.begin());
  }
  std::vector<std::array<int, 3>> bins_;
  std::array<std::array<double, kBins>, 3> want_{}, have_{};
  double count_ = 0.0;
};

struct Block {
  Vec2 source;  // the exemplar square's centre
  Vec2 centre;  // where it lands
};

}  // namespace

std::vector<QuiltLine> quilt_lines(const Network& exemplar, const QuiltSettings& settings,
                                   SplitMix64& rng) {
  Vec2 elo{INFINITY, INFINITY}, ehi{-INFINITY, -INFINITY};
  Segments lines;
  for (std::size_t i = 0; i < exemplar.edges.size(); ++i) {
    for (Vec2 p : exemplar.edges[i].points)
      elo = {std::min(elo.x, p.x), std::min(elo.y, p.y)},
      ehi = {std::max(ehi.x, p.x), std::max(ehi.y, p.y)};
    insert_line(lines, exemplar.edges[i].points, int(i));
  }
  const double shorter = std::min(ehi.x - elo.x, ehi.y - elo.y);
  if (!(shorter > 0.0)) return {};  // lines along one line: no square to copy
  const double overlap = kOverlapFraction * kBlockFraction * shorter;
  const double stride = kBlockFraction * shorter - overlap;
  const Vec2 lo = settings.lo, hi = settings.hi;
  const int nx = std::max(1, int(std::ceil((hi.x - lo.x) / stride)));
  const int ny = std::max(1, int(std::ceil((hi.y - lo.y) / stride)));
  const Vec2 cell{(hi.x - lo.x) / nx, (hi.y - lo.y) / ny};
  const double side = std::max(cell.x, cell.y) + overlap;  // a block: its cell and a margin
  const double half = 0.5 * side, cap = 0.5 * overlap;

  // Squares mostly off the exemplar's lines (the sea beside a county map) are not taken: more
  // than one of 5 × 5 points farther from any line than 3 × the exemplar's median distance.
  std::vector<double> gaps;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i)
      gaps.push_back(nearest(
          lines,
          {elo.x + (i + 0.5) * (ehi.x - elo.x) / 32, elo.y + (j + 0.5) * (ehi.y - elo.y) / 32},
          INFINITY));
  std::nth_element(gaps.begin(), gaps.begin() + long(gaps.size() / 2), gaps.end());
  const double empty = 3.0 * gaps[gaps.size() / 2];
  const DistanceField field(lines, elo, ehi, overlap / 8.0, 2.0 * std::max(cap, empty));
  const auto to_exemplar = [&](const Block& b, Vec2 q) {
    return rotated(q - b.centre, -settings.turn) + b.source;
  };
  const auto mostly_empty = [&](const Block& b) {
    int far = 0;
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const Vec2 q = b.centre + Vec2{(i - 2) * 0.225 * side, (j - 2) * 0.225 * side};
        far += field.at(to_exemplar(b, q)) > empty;
      }
    return far > 1;
  };
  const auto random_source = [&]() {
    const auto pick = [&](double a, double b) {
      return b - a > side ? rng.uniform(a + half, b - half) : 0.5 * (a + b);
    };
    return Vec2{pick(elo.x, ehi.x), pick(elo.y, ehi.y)};
  };

  // Blocks in rows from the region's lower left; each compared with the blocks below and to its
  // left in their overlap.
  // The exemplar edges whose middle vertex a block puts in the cell [c0, c1].
  std::vector<int> in_cell;
  std::vector<SegValue> hits;
  const auto edges_in_cell = [&](const Block& b, Vec2 c0, Vec2 c1) -> const std::vector<int>& {
    in_cell.clear();
    hits.clear();
    const double r = 0.5 * std::sqrt(2.0) * std::max(c1.x - c0.x, c1.y - c0.y);
    lines.query(bgi::intersects(BgBox(to_bg(b.source - Vec2{r, r}), to_bg(b.source + Vec2{r, r}))),
                std::back_inserter(hits));
    for (const SegValue& v : hits) in_cell.push_back(v.second);
    std::sort(in_cell.begin(), in_cell.end());
    in_cell.erase(std::unique(in_cell.begin(), in_cell.end()), in_cell.end());
    std::erase_if(in_cell, [&](int e) {
      const auto& pts = exemplar.edges[std::size_t(e)].points;
      const Vec2 q = rotated(pts[pts.size() / 2] - b.source, settings.turn) + b.centre;
      return !(q.x >= c0.x && q.x < c1.x && q.y >= c0.y && q.y < c1.y);
    });
    return in_cell;
  };
  QuiltTraits traits(exemplar);
  std::vector<std::pair<double, Block>> scored;
  Segments placed;
  std::vector<std::vector<std::vector<Vec2>>> content(std::size_t(nx) * std::size_t(ny));
  // Per block, the exemplar's edges moved there uncut, and per line of `content` the one it was
  // cut from: a seam end's continuation is read from it.
  std::vector<std::vector<std::vector<Vec2>>> whole(content.size());
  std::vector<std::vector<std::size_t>> cut_from(content.size());
  const double step = 0.25 * overlap;
  const int along = std::max(2, int(std::ceil(side / step))), across = 5;
  std::vector<Vec2> samples;
  std::vector<double> placed_distance;
  std::vector<SegValue> found;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c0{lo.x + i * cell.x, lo.y + j * cell.y};
      const Vec2 centre = c0 + 0.5 * cell;
      samples.clear();
      for (int a = 0; a <= along; ++a)
        for (int k = 0; k < across; ++k) {
          const double u = centre.x - half + side * a / along;
          const double v = centre.y - half + side * a / along;
          const double w = (k - 2) * 0.5 * overlap / 2;
          if (i > 0) samples.push_back({c0.x + w, v});
          if (j > 0) samples.push_back({u, c0.y + w});
        }
      placed_distance.clear();
      for (Vec2 q : samples) placed_distance.push_back(nearest(placed, q, cap));
      const auto cost_of = [&](const Block& b, double bound) {
        double cost = 0.0;
        for (std::size_t s = 0; s < samples.size() && cost < bound; ++s) {
          const double d = std::min(cap, field.at(to_exemplar(b, samples[s]))) - placed_distance[s];
          cost += d * d;
        }
        return cost;
      };
      scored.clear();
      for (int attempt = 0;
           int(scored.size()) < settings.candidates && attempt < 8 * settings.candidates;
           ++attempt) {
        const Block b{random_source(), centre};
        if (attempt + 1 < 8 * settings.candidates && mostly_empty(b)) continue;
        scored.push_back({cost_of(b, INFINITY), b});
      }
      // Of the few that agree best with the neighbours, the one whose edges bring the traits
      // placed so far closest to the exemplar's (a choice by the seam alone favours the parts of
      // the exemplar whose lines are easiest to continue: straight ones).
      const std::size_t shortlist = std::min(scored.size(), std::size_t(kShortlist));
      std::partial_sort(scored.begin(), scored.begin() + long(shortlist), scored.end(),
                        [](const auto& x, const auto& y) { return x.first < y.first; });
      Block best = scored[0].second;
      double best_cost = scored[0].first, best_mismatch = INFINITY;
      for (std::size_t k = 0; k < shortlist; ++k) {
        const double m = traits.mismatch(edges_in_cell(scored[k].second, c0, c0 + cell));
        if (m < best_mismatch - 1e-12)
          best_mismatch = m, best = scored[k].second, best_cost = scored[k].first;
      }
      // The best candidate slid to where its lines agree best with the neighbours' (a descent
      // over the source's offset, halving the step): lattices (grids, cells of one size) line
      // up across the seam instead of meeting it at a random phase.
      for (double slide = 0.25 * overlap; !samples.empty() && slide > 0.02 * overlap;) {
        bool moved = false;
        for (int k = 0; k < 8; ++k) {
          const double a = k * std::numbers::pi / 4;
          const Block b{best.source + slide * Vec2{std::cos(a), std::sin(a)}, centre};
          if (b.source.x - half < elo.x || b.source.x + half > ehi.x || b.source.y - half < elo.y ||
              b.source.y + half > ehi.y)
            continue;
          const double cost = cost_of(b, best_cost);
          if (cost < best_cost) best_cost = cost, best = b, moved = true;
        }
        if (!moved) slide *= 0.5;
      }
      traits.add(edges_in_cell(best, c0, c0 + cell));
      // The block's lines: the exemplar's edges under its square, moved and cut to it.
      const double reach = half * std::sqrt(2.0);
      found.clear();
      lines.query(bgi::intersects(BgBox(to_bg(best.source - Vec2{reach, reach}),
                                        to_bg(best.source + Vec2{reach, reach}))),
                  std::back_inserter(found));
      std::vector<int> edges;
      for (const SegValue& v : found) edges.push_back(v.second);
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      const std::size_t block = std::size_t(j) * std::size_t(nx) + std::size_t(i);
      auto& mine = content[block];
      for (int e : edges) {
        std::vector<Vec2> moved;
        for (Vec2 p : exemplar.edges[std::size_t(e)].points)
          moved.push_back(rotated(p - best.source, settings.turn) + best.centre);
        cut_to_box(moved, centre - Vec2{half, half}, centre + Vec2{half, half}, mine);
        cut_from[block].resize(mine.size(), whole[block].size());
        whole[block].push_back(std::move(moved));
      }
      for (const auto& line : mine) insert_line(placed, line, j * nx + i);
    }

  // The cuts between the blocks, each moved within the overlap to where the fewest lines run
  // along it (image quilting's minimum-error boundary, for lines: a line running beside the cut
  // would come twice, once from each block): one horizontal cut per pair of rows, then one
  // vertical cut per pair of neighbours within a row, so that the cells still tile the region.
  const auto block_lines = [&](int i, int j) -> const std::vector<std::vector<Vec2>>& {
    return content[std::size_t(j) * std::size_t(nx) + std::size_t(i)];
  };
  const double band = 2.0 * settings.clearance;
  // The length of the lines of `blocks` running within `band` of the line {axis = at}, at less
  // than 30° from it, with their other coordinate in [from, to].
  const auto along_length = [&](const std::vector<std::pair<int, int>>& blocks, bool vertical,
                                double at, double from, double to) {
    double total = 0.0;
    for (const auto& [i, j] : blocks)
      for (const auto& line : block_lines(i, j))
        for (std::size_t k = 0; k + 1 < line.size(); ++k) {
          Vec2 a = line[k], b = line[k + 1];
          if (!vertical) std::swap(a.x, a.y), std::swap(b.x, b.y);
          const Vec2 d = b - a;
          const double size = length(d);
          if (!(size > 0.0) || std::abs(d.x) > 0.5 * size) continue;
          double t0 = 0.0, t1 = 1.0;
          const auto keep = [&](double p, double q, double lo_, double hi_) {  // p + q t in range
            if (q == 0.0) {
              if (p < lo_ || p > hi_) t1 = -1.0;
              return;
            }
            double u = (lo_ - p) / q, v = (hi_ - p) / q;
            if (u > v) std::swap(u, v);
            t0 = std::max(t0, u), t1 = std::min(t1, v);
          };
          keep(a.x, d.x, at - band, at + band);
          keep(a.y, d.y, from, to);
          if (t1 > t0) total += (t1 - t0) * size;
        }
    return total;
  };
  const auto best_cut = [&](const std::vector<std::pair<int, int>>& blocks, bool vertical,
                            double nominal, double from, double to) {
    double best = nominal, best_length = INFINITY;
    for (int k = 0; k <= 16; ++k) {  // from the nominal cut outward
      const double offset = 0.4 * overlap * ((k + 1) / 2) / 8.0 * (k % 2 ? 1.0 : -1.0);
      const double length = along_length(blocks, vertical, nominal + offset, from, to);
      if (length < best_length - 1e-9) best_length = length, best = nominal + offset;
    }
    return best;
  };
  std::vector<double> row_cut(std::size_t(ny) + 1);
  row_cut[0] = lo.y, row_cut[std::size_t(ny)] = hi.y;
  for (int j = 1; j < ny; ++j) {
    std::vector<std::pair<int, int>> blocks;
    for (int i = 0; i < nx; ++i) blocks.push_back({i, j - 1}), blocks.push_back({i, j});
    row_cut[std::size_t(j)] = best_cut(blocks, false, lo.y + j * cell.y, lo.x, hi.x);
  }
  std::vector<double> column_cut(std::size_t(nx + 1) * std::size_t(ny));
  const auto cut_x = [&](int i, int j) -> double& {
    return column_cut[std::size_t(j) * std::size_t(nx + 1) + std::size_t(i)];
  };
  for (int j = 0; j < ny; ++j) {
    cut_x(0, j) = lo.x, cut_x(nx, j) = hi.x;
    for (int i = 1; i < nx; ++i)
      cut_x(i, j) = best_cut({{i - 1, j}, {i, j}}, true, lo.x + i * cell.x, row_cut[std::size_t(j)],
                             row_cut[std::size_t(j) + 1]);
  }

  // Each block cut to its cell; ends on a side shared with another cell are seam ends.
  std::vector<QuiltLine> out;
  const double eps = 1e-9 * std::max(1.0, side);
  std::vector<std::vector<Vec2>> parts;
  std::vector<std::size_t> part_from;
  std::vector<std::tuple<int, int, int>> ends;  // line, end, cell
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c0{cut_x(i, j), row_cut[std::size_t(j)]};
      const Vec2 c1{cut_x(i + 1, j), row_cut[std::size_t(j) + 1]};
      const std::size_t block = std::size_t(j) * std::size_t(nx) + std::size_t(i);
      parts.clear();
      part_from.clear();
      for (std::size_t l = 0; l < content[block].size(); ++l) {
        cut_to_box(content[block][l], c0, c1, parts);
        part_from.resize(parts.size(), cut_from[block][l]);
      }
      for (std::size_t k = 0; k < parts.size(); ++k) {
        auto& part = parts[k];
        if (polyline_length(part) <= eps) continue;
        QuiltLine q;
        q.points = std::move(part);
        for (int end = 0; end < 2; ++end) {
          const Vec2 p = end == 0 ? q.points.front() : q.points.back();
          q.seam_end[end] = (i > 0 && std::abs(p.x - c0.x) <= eps) ||
                            (i + 1 < nx && std::abs(p.x - c1.x) <= eps) ||
                            (j > 0 && std::abs(p.y - c0.y) <= eps) ||
                            (j + 1 < ny && std::abs(p.y - c1.y) <= eps);
        }
        // A sliver between two seams (a line grazing a cell's corner) is left out: stitched, it
        // would join its neighbours by a kink or close a tiny ring with another sliver; without
        // it they meet across the gap as any two seam ends do.
        if (q.seam_end[0] && q.seam_end[1] &&
            polyline_length(q.points) < kSliverFraction * settings.stitch)
          continue;
        for (int end = 0; end < 2; ++end) {
          if (!q.seam_end[end]) continue;
          ends.push_back({int(out.size()), end, j * nx + i});
          q.continuation[end] =
              continuation_of(whole[block][part_from[k]], end == 0 ? q.points[0] : q.points.back(),
                              inner_vertex(q.points, end), settings.continuation);
        }
        out.push_back(std::move(q));
      }
    }

  // Stitching: pairs of seam ends from different cells, closer than the stitch radius and
  // crossing the seam nearly in line, the closest pairs first, joined at their midpoint.
  const auto end_point = [&](int line, int end) {
    const auto& p = out[std::size_t(line)].points;
    return end == 0 ? p.front() : p.back();
  };
  const auto outward = [&](int line, int end) {
    const auto& p = out[std::size_t(line)].points;
    return end == 0 ? normalized(p[0] - p[1]) : normalized(p.back() - p[p.size() - 2]);
  };
  bgi::rtree<EndValue, bgi::quadratic<16>> end_index;
  for (std::size_t k = 0; k < ends.size(); ++k)
    end_index.insert({to_bg(end_point(std::get<0>(ends[k]), std::get<1>(ends[k]))), int(k)});
  std::vector<std::tuple<double, int, int>> pairs;
  std::vector<EndValue> near;
  for (std::size_t a = 0; a < ends.size(); ++a) {
    const auto [la, ea, ca] = ends[a];
    const Vec2 p = end_point(la, ea);
    near.clear();
    end_index.query(bgi::intersects(BgBox(to_bg(p - Vec2{settings.stitch, settings.stitch}),
                                          to_bg(p + Vec2{settings.stitch, settings.stitch}))),
                    std::back_inserter(near));
    for (const EndValue& v : near) {
      const auto [lb, eb, cb] = ends[std::size_t(v.second)];
      if (v.second <= int(a) || cb == ca || lb == la) continue;
      const double d = distance(p, end_point(lb, eb));
      if (d < settings.stitch && dot(outward(la, ea), outward(lb, eb)) < -kStitchCos)
        pairs.push_back({d, int(a), v.second});
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> joined(ends.size(), 0);
  for (const auto& [d, a, b] : pairs) {
    if (joined[std::size_t(a)] || joined[std::size_t(b)]) continue;
    joined[std::size_t(a)] = joined[std::size_t(b)] = 1;
    const auto [la, ea, ca] = ends[std::size_t(a)];
    const auto [lb, eb, cb] = ends[std::size_t(b)];
    // Joined on the straight line between the vertices before the two ends, so that the joint
    // turns nothing: two straight lines cut at the seam become one straight line (only the last
    // segment of each moves).
    auto& pa = out[std::size_t(la)].points;
    auto& pb = out[std::size_t(lb)].points;
    const Vec2 ia = inner_vertex(pa, ea), ib = inner_vertex(pb, eb);
    const double da = distance(ia, end_vertex(pa, ea)), db = distance(ib, end_vertex(pb, eb));
    const Vec2 m = lerp(ia, ib, da + db > 0.0 ? da / (da + db) : 0.5);
    end_vertex(pa, ea) = m;
    end_vertex(pb, eb) = m;
  }
  return out;
}

}  // namespace tw::network_detail
