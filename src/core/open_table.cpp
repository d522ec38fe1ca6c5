#include "open_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "robust_sigma.hpp"

namespace lccp::detail {

OpenTable::OpenTable(const CloudView& cloud, const std::vector<std::uint8_t>& open, const Plane& support,
                     float cell_m)
    : e1_(support.normal.unitOrthogonal()), e2_(support.normal.cross(e1_)), cell_m_(cell_m) {
  const auto in_plane = [&](std::size_t i) {
    return Eigen::Vector2f(cloud.points[i].dot(e1_), cloud.points[i].dot(e2_));
  };
  Eigen::Vector2f low = Eigen::Vector2f::Constant(std::numeric_limits<float>::infinity()), high = -low;
  double count = 0;
  for (std::size_t i = 0; i < open.size(); ++i) {
    if (open[i]) low = low.cwiseMin(in_plane(i)), high = high.cwiseMax(in_plane(i)), count += 1;
  }
  if (count == 0) return;
  low_ = low;
  // Never more cells than points (a sparse cloud spread over a large plane): coarser cells.
  const auto cells_across = [&](float extent) { return static_cast<long>(extent / cell_m_) + 1; };
  while (double(cells_across(high.x() - low.x())) * double(cells_across(high.y() - low.y())) > count) cell_m_ *= 2;
  columns_ = cells_across(high.x() - low.x()), rows_ = cells_across(high.y() - low.y());
  cells_.resize(static_cast<std::size_t>(columns_ * rows_));
  for (std::size_t i = 0; i < open.size(); ++i) {
    const long cell = open[i] ? cell_of(cloud.points[i]) : -1;
    if (cell >= 0) cells_[static_cast<std::size_t>(cell)].add(support.distance(cloud.points[i]));
  }
}

long OpenTable::cell_of(const Eigen::Vector3f& p) const {
  const Eigen::Vector2f uv = (Eigen::Vector2f(p.dot(e1_), p.dot(e2_)) - low_) / cell_m_;
  if (!(uv.x() >= 0 && uv.y() >= 0 && uv.x() < float(columns_) && uv.y() < float(rows_))) return -1;
  return static_cast<long>(uv.y()) * columns_ + static_cast<long>(uv.x());
}

void OpenTable::around(long cell, std::vector<long>& out) const {
  out.clear();
  for_each_around(cell, [&](long c) { out.push_back(c); });
}

HeightSum OpenTable::sum_around(long cell) const {
  HeightSum sum;
  for_each_around(cell, [&](long c) { sum.add(at(c)); });
  return sum;
}

float OpenTable::flatness_m() const {
  std::vector<float> differences;
  std::vector<long> near;
  for (long cell = 0; cell < static_cast<long>(cells_.size()); ++cell) {
    if (at(cell).points < kMinPoints) continue;
    HeightSum others;
    around(cell, near);
    for (const long n : near) {
      if (n != cell && at(n).points >= kMinPoints) others.add(at(n));
    }
    if (others.points == 0) continue;
    const double mean = at(cell).height / at(cell).points;
    differences.push_back(static_cast<float>(std::abs(mean - others.height / others.points)));
  }
  return robust_sigma(differences);
}

}  // namespace lccp::detail
