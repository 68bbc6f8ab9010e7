#include "network/detail/quilt.hpp"

#include <algorithm>
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

Vec2 rotate(Vec2 v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

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
    return rotate(q - b.centre, -settings.turn) + b.source;
  };
  const auto mostly_empty = [&](const Block& b) {
    int far = 0;
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const Vec2 q = b.centre + Vec2{(i - 2) * 0.45 * side, (j - 2) * 0.45 * side};
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
  Segments placed;
  std::vector<std::vector<std::vector<Vec2>>> content(std::size_t(nx) * std::size_t(ny));
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
      Block best{};
      double best_cost = INFINITY;
      int tried = 0;
      for (int attempt = 0; tried < settings.candidates && attempt < 8 * settings.candidates;
           ++attempt) {
        const Block b{random_source(), centre};
        if (attempt + 1 < 8 * settings.candidates && mostly_empty(b)) continue;
        ++tried;
        const double cost = cost_of(b, best_cost);
        if (cost < best_cost) best_cost = cost, best = b;
        if (samples.empty()) break;
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
      auto& mine = content[std::size_t(j) * std::size_t(nx) + std::size_t(i)];
      for (int e : edges) {
        std::vector<Vec2> moved;
        for (Vec2 p : exemplar.edges[std::size_t(e)].points)
          moved.push_back(rotate(p - best.source, settings.turn) + best.centre);
        cut_to_box(moved, centre - Vec2{half, half}, centre + Vec2{half, half}, mine);
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
  std::vector<std::tuple<int, int, int>> ends;  // line, end, cell
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c0{cut_x(i, j), row_cut[std::size_t(j)]};
      const Vec2 c1{cut_x(i + 1, j), row_cut[std::size_t(j) + 1]};
      parts.clear();
      for (const auto& line : block_lines(i, j)) cut_to_box(line, c0, c1, parts);
      for (auto& part : parts) {
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
        for (int end = 0; end < 2; ++end)
          if (q.seam_end[end]) ends.push_back({int(out.size()), end, j * nx + i});
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
