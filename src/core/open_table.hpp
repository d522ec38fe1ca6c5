#pragma once
// Internal: the open table (SupportPlaneConfig::decided_by_patches), the band
// points left out because no other point is near them, as a grid of cells in
// the support's plane: the local height of the support, against which a band
// region near the objects is compared (settle_support in lccp.cpp).
#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lccp/cloud.hpp"
#include "lccp/core/support_plane.hpp"

namespace lccp::detail {

// Band points' heights above the support's plane, summed, and their count.
struct HeightSum {
  double height = 0, points = 0;
  void add(double h, double n = 1) { height += h, points += n; }
  void add(const HeightSum& other) { add(other.height, other.points); }
};

class OpenTable {
 public:
  // The points i with open[i] != 0, in square cells `cell_m` wide of the
  // plane of `support` (or wider, by powers of 2, to keep the cells no more
  // than the points).
  OpenTable(const CloudView& cloud, const std::vector<std::uint8_t>& open, const Plane& support, float cell_m);

  // The cell of a point (its index in the grid), or -1 outside the grid.
  long cell_of(const Eigen::Vector3f& p) const;
  // The cell's neighbours and itself (up to 9, inside the grid), into `out`.
  void around(long cell, std::vector<long>& out) const;
  // The open points' heights in those cells, summed.
  HeightSum sum_around(long cell) const;
  const HeightSum& at(long cell) const { return cells_[static_cast<std::size_t>(cell)]; }
  std::size_t size() const { return cells_.size(); }

  // How much the support departs from a plane between cells: the robust
  // standard deviation (robust_sigma) of the difference between a cell's mean
  // height and the mean of its neighbours', over cells of at least kMinPoints
  // points (their means within a quarter of one point's noise); 0 without
  // such cells.
  float flatness_m() const;

 private:
  template <typename Visit>
  void for_each_around(long cell, Visit visit) const {
    const long row = cell / columns_, column = cell % columns_;
    for (long r = std::max(0L, row - 1); r <= std::min(rows_ - 1, row + 1); ++r) {
      for (long c = std::max(0L, column - 1); c <= std::min(columns_ - 1, column + 1); ++c) visit(r * columns_ + c);
    }
  }

  static constexpr double kMinPoints = 20;
  Eigen::Vector3f e1_, e2_;
  float cell_m_ = 0;
  Eigen::Vector2f low_ = Eigen::Vector2f::Zero();
  long columns_ = 0, rows_ = 0;
  std::vector<HeightSum> cells_;
};

}  // namespace lccp::detail
