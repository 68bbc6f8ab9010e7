#include "sketch/detail/clustering.hpp"

#include <Eigen/Dense>
#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tw::detail {

namespace {

// nanoflann's dataset adaptor over 2-D points.
struct PointCloud {
  const std::vector<Eigen::Vector2d>& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][int(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>,
                                                   PointCloud, 2>;

// Flat-kernel mean shift on 2-D points; modes closer than half the bandwidth are one cluster.
std::vector<int> mean_shift(const std::vector<Eigen::Vector2d>& points, double bandwidth) {
  PointCloud cloud{points};
  KdTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  const double radius2 = bandwidth * bandwidth;
  std::vector<Eigen::Vector2d> modes;
  std::vector<int> labels(points.size(), -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d x = points[i];
    for (int iteration = 0; iteration < 200; ++iteration) {
      std::vector<std::pair<unsigned, double>> found;
      tree.radiusSearch(x.data(), radius2, found, nanoflann::SearchParams(32, 0.0f, false));
      // Summed in index order: the same mean whatever order the tree returns.
      std::sort(found.begin(), found.end());
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto& f : found) mean += points[f.first];
      mean /= double(found.size());  // x starts on a point and stays in its hull: never empty
      const bool converged = (mean - x).norm() < 1e-9 * std::max(1.0, bandwidth);
      x = mean;
      if (converged) break;
    }
    for (std::size_t m = 0; m < modes.size(); ++m) {
      if ((modes[m] - x).norm() < 0.5 * bandwidth) {
        labels[i] = int(m);
        break;
      }
    }
    if (labels[i] < 0) {
      labels[i] = int(modes.size());
      modes.push_back(x);
    }
  }
  return labels;
}

}  // namespace

std::vector<int> mean_shift_1d(const std::vector<double>& values, double bandwidth) {
  std::vector<Eigen::Vector2d> points;
  for (double v : values) points.emplace_back(v, 0.0);
  return mean_shift(points, bandwidth);
}

std::vector<int> mean_shift_axial(const std::vector<double>& angles, double bandwidth) {
  // On the circle of doubled angles, where 0 and pi meet; a chord of 2 sin(b) spans b radians
  // of orientation.
  std::vector<Eigen::Vector2d> points;
  for (double a : angles) points.emplace_back(std::cos(2.0 * a), std::sin(2.0 * a));
  return mean_shift(points, 2.0 * std::sin(std::min(bandwidth, 1.5)));
}

double axial_mean(const std::vector<double>& angles) {
  double c = 0.0, s = 0.0;
  for (double a : angles) c += std::cos(2.0 * a), s += std::sin(2.0 * a);
  double mean = 0.5 * std::atan2(s, c);
  if (mean < 0.0) mean += std::numbers::pi;
  return mean;
}

double axial_sd(const std::vector<double>& angles) {
  if (angles.size() < 2) return 0.0;
  double c = 0.0, s = 0.0;
  for (double a : angles) c += std::cos(2.0 * a), s += std::sin(2.0 * a);
  const double r = std::min(1.0, std::hypot(c, s) / double(angles.size()));
  // Circular sd of the doubled angles, halved back to orientations.
  return r <= 0.0 ? std::numbers::pi / 2 : 0.5 * std::sqrt(-2.0 * std::log(r));
}

Vec2 direction_of(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

OrientedBox principal_box(const std::vector<Vec2>& points, double pad) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (Vec2 p : points) mean += Eigen::Vector2d(p.x, p.y);
  mean /= double(points.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (Vec2 p : points) {
    const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
  const Eigen::Vector2d major = solver.eigenvectors().col(1);  // ascending eigenvalues
  const Vec2 axis = direction_of(line_angle({major.x(), major.y()}));
  const Vec2 normal = perp(axis);
  double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
  for (Vec2 p : points) {
    a0 = std::min(a0, dot(p, axis)), a1 = std::max(a1, dot(p, axis));
    b0 = std::min(b0, dot(p, normal)), b1 = std::max(b1, dot(p, normal));
  }
  OrientedBox box;
  box.axis = axis;
  box.center = axis * (0.5 * (a0 + a1)) + normal * (0.5 * (b0 + b1));
  box.half_length = 0.5 * (a1 - a0) + pad;
  box.half_width = 0.5 * (b1 - b0) + pad;
  return box;
}

std::vector<Vec2> nearest_neighbour_vectors(const std::vector<Vec2>& points) {
  std::vector<Eigen::Vector2d> cloud_points;
  for (Vec2 p : points) cloud_points.emplace_back(p.x, p.y);
  PointCloud cloud{cloud_points};
  KdTree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  std::vector<Vec2> out(points.size());
  if (points.size() < 2) return out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    unsigned index[2];
    double d2[2];
    tree.knnSearch(cloud_points[i].data(), 2, index, d2);
    const unsigned other = index[0] == i ? index[1] : index[0];
    out[i] = points[other] - points[i];
  }
  return out;
}

}  // namespace tw::detail
