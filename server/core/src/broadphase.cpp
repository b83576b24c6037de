#include "physics/broadphase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/formulas.h"

namespace phys {

namespace {

constexpr std::uint32_t kLarge = UINT32_MAX;
// Boxes larger than this many median boxes are not filed in cells; they are tested
// against everything (a floor or a wall: few, and everyone touches them anyway).
constexpr double kLargeInMedians = 4.0;
// At most this many cells per indexed box, so sparse scenes do not allocate a sea
// of empty cells.
constexpr double kCellsPerBox = 2.0;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Centres farther than this from the origin are not filed in cells (see build); the
// core refuses positions beyond kMaxCoordinate = 1e7, so only a body that drifted
// there, a hundred times the limit, ever lands in the large list this way.
constexpr double kFarCentre = 1.0e9;
// Passes of the cell-growing loop: from 1e-9 by 1.25 a pass reaches 2e9 within 200.
constexpr int kMaxGrowPasses = 256;

// boxes_intersect without its short-circuit: all four tests, no branch. The pair
// loops below test boxes that overlap about half the time, a branch the hardware
// mispredicts as often; these compile to compares and ands.
// (The same four conditions as boxes_intersect, NaN included.)
bool boxes_overlap_branchless(const Aabb& a, const Aabb& b) {
  const int apart = static_cast<int>(box_bottom_above_top(a, b)) |
                    static_cast<int>(box_top_below_bottom(a, b)) |
                    static_cast<int>(box_left_right_of_right(a, b)) |
                    static_cast<int>(box_right_left_of_left(a, b));
  return apart == 0;
}

double extent_of(const Aabb& b) { return std::max(b.max.x - b.min.x, b.max.y - b.min.y); }
bool finite_box(const Aabb& b) { return is_finite(b.min) && is_finite(b.max); }
Vec2 center_of(const Aabb& b) { return (b.min + b.max) * 0.5; }

}  // namespace

void find_pairs_brute_force(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  out.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
      if (boxes_intersect(boxes[i], boxes[j])) out.push_back({i, j});
    }
  }
}

std::int32_t UniformGrid::cell_x(double x) const {
  const double v = (x - origin_.x) * inv_cell_;
  if (!(v > 0.0)) return 0;  // also NaN
  if (v >= static_cast<double>(columns_ - 1)) return columns_ - 1;
  return static_cast<std::int32_t>(v);  // truncation is floor for v > 0
}

std::int32_t UniformGrid::cell_y(double y) const {
  const double v = (y - origin_.y) * inv_cell_;
  if (!(v > 0.0)) return 0;
  if (v >= static_cast<double>(rows_ - 1)) return rows_ - 1;
  return static_cast<std::int32_t>(v);
}

// Long on purpose: the cell size, its growth and the counting sort share the sizes and
// scratch the steps before them compute; each step is commented where it starts.
void UniformGrid::build(std::span<const Aabb> boxes) {
  boxes_.assign(boxes.begin(), boxes.end());
  const auto n = static_cast<std::uint32_t>(boxes_.size());
  large_.clear();
  cell_of_.assign(n, kLarge);
  cell_items_.clear();
  columns_ = rows_ = 0;
  cell_start_.assign(1, 0);
  if (n == 0) return;

  std::vector<double>& extents = extents_;
  extents.clear();
  for (const Aabb& b : boxes_) {
    if (finite_box(b)) extents.push_back(extent_of(b));
  }
  double median = 0.0;
  if (!extents.empty()) {
    auto middle = extents.begin() + static_cast<std::ptrdiff_t>(extents.size() / 2);
    std::nth_element(extents.begin(), middle, extents.end());
    median = *middle;
  }
  const double large_above = std::max(kLargeInMedians * median, 1.0e-9);

  // The cell is as large as the largest ordinary box, so overlapping boxes have
  // their centres in the same or adjacent cells. A box whose centre lies beyond
  // kFarCentre is kept with the large ones (tested against everything): the spread
  // of the filed centres then stays a finite number, whatever the world was given.
  Vec2 lo{kInf, kInf};
  Vec2 hi{-kInf, -kInf};
  double cell = 1.0e-9;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb& b = boxes_[i];
    const double extent = finite_box(b) ? extent_of(b) : kInf;
    const Vec2 c = center_of(b);
    if (extent > large_above || !(std::fabs(c.x) <= kFarCentre && std::fabs(c.y) <= kFarCentre)) {
      large_.push_back(i);
      continue;
    }
    cell = std::max(cell, extent);
    lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
    hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
  }
  if (large_.size() == n) return;
  reach_ = 0.5 * cell;

  // Grow the cells until the grid has no more than kCellsPerBox cells per box. The
  // cell grows by 1.25 at least each pass, so the spread (at most 2 * kFarCentre)
  // is covered within a bounded number of passes; past kMaxGrowPasses (never reached
  // with finite centres) the grid is one cell, which tests every filed pair.
  const double budget = std::max(64.0, kCellsPerBox * static_cast<double>(n));
  columns_ = rows_ = 1;
  for (int pass = 0; pass < kMaxGrowPasses; ++pass) {
    const double cols = std::floor((hi.x - lo.x) / cell) + 1.0;
    const double rows = std::floor((hi.y - lo.y) / cell) + 1.0;
    if (cols * rows <= budget) {
      columns_ = static_cast<std::int32_t>(cols);
      rows_ = static_cast<std::int32_t>(rows);
      break;
    }
    cell *= std::max(1.25, std::sqrt(cols * rows / budget));
  }
  cell_size_ = cell;
  inv_cell_ = 1.0 / cell;
  origin_ = lo;

  // Counting sort by cell: each cell's boxes come out in ascending index.
  const std::size_t cells = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  cell_start_.assign(cells + 1, 0);
  std::size_t next_large = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (next_large < large_.size() && large_[next_large] == i) {
      ++next_large;
      continue;
    }
    const Vec2 c = center_of(boxes_[i]);
    const auto index = static_cast<std::uint32_t>(cell_y(c.y) * columns_ + cell_x(c.x));
    cell_of_[i] = index;
    ++cell_start_[index + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(cell_start_[cells]);
  std::vector<std::uint32_t>& fill = fill_;
  fill.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (cell_of_[i] != kLarge) cell_items_[fill[cell_of_[i]]++] = i;
  }
  cell_boxes_.resize(cell_items_.size());
  for (std::size_t k = 0; k < cell_items_.size(); ++k) cell_boxes_[k] = boxes_[cell_items_[k]];
}

// Long on purpose: the branch-free cell loops, the large boxes and the final sort share
// one output buffer and its running end, kept in registers across the loops.
void UniformGrid::find_pairs(std::vector<BodyPair>& out) const {
  // Each cell is tested against itself and four of its neighbours (east, and the
  // three above), so every pair of filed boxes is tested exactly once: the cells
  // are as large as the largest filed box, so overlapping boxes sit in the same
  // or adjacent cells.
  auto& found = unsorted_;
  found.clear();
  const auto emit = [&found](std::uint32_t i, std::uint32_t j) {
    found.push_back(i < j ? BodyPair{i, j} : BodyPair{j, i});
  };
  // The cell pairs are written without a branch: every tested pair is stored at
  // the end, and the end moves on only if the boxes overlap. Room for all the
  // pairs a box can have is made before its loops.
  std::size_t count = 0;
  const auto test_range = [&](std::uint32_t item, const Aabb& box, std::uint32_t from,
                              std::uint32_t to) {
    BodyPair* const pairs = found.data();
    for (std::uint32_t m = from; m < to; ++m) {
      const std::uint32_t other = cell_items_[m];
      pairs[count] = {std::min(item, other), std::max(item, other)};
      count += static_cast<std::size_t>(boxes_overlap_branchless(box, cell_boxes_[m]));
    }
  };
  for (std::int32_t cy = 0; cy < rows_; ++cy) {
    for (std::int32_t cx = 0; cx < columns_; ++cx) {
      const std::uint32_t cell = static_cast<std::uint32_t>(cy * columns_ + cx);
      const std::uint32_t begin = cell_start_[cell];
      const std::uint32_t end = cell_start_[cell + 1];
      if (begin == end) continue;
      // Neighbour ranges: east in this row, then west..east in the row above.
      std::uint32_t ranges[3][2];
      int range_count = 0;
      if (cx + 1 < columns_) {
        ranges[range_count][0] = cell_start_[cell + 1];
        ranges[range_count++][1] = cell_start_[cell + 2];
      }
      if (cy + 1 < rows_) {
        const std::uint32_t above = cell + static_cast<std::uint32_t>(columns_);
        const std::uint32_t west = cx > 0 ? above - 1 : above;
        const std::uint32_t east = cx + 1 < columns_ ? above + 1 : above;
        ranges[range_count][0] = cell_start_[west];
        ranges[range_count++][1] = cell_start_[east + 1];
      }
      std::size_t room = end - begin;
      for (int r = 0; r < range_count; ++r) room += ranges[r][1] - ranges[r][0];
      for (std::uint32_t k = begin; k < end; ++k) {
        if (count + room > found.size()) found.resize(std::max(2 * found.size(), count + room));
        const Aabb bk = cell_boxes_[k];
        const std::uint32_t item = cell_items_[k];
        test_range(item, bk, k + 1, end);
        for (int r = 0; r < range_count; ++r) test_range(item, bk, ranges[r][0], ranges[r][1]);
      }
    }
  }
  found.resize(count);
  // Large boxes against everything (each pair of two large boxes once).
  const auto n = static_cast<std::uint32_t>(boxes_.size());
  for (std::uint32_t large : large_) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == large || (cell_of_[j] == kLarge && j < large)) continue;
      if (boxes_intersect(boxes_[large], boxes_[j])) emit(large, j);
    }
  }

  // Counting sort by the first index, then each group by the second: the order
  // depends on the inputs alone, as documented (i ascending, then j ascending).
  group_start_.assign(n + 1, 0);
  for (const BodyPair& p : found) ++group_start_[p.a + 1];
  for (std::uint32_t i = 0; i < n; ++i) group_start_[i + 1] += group_start_[i];
  out.resize(found.size());
  for (const BodyPair& p : found) out[group_start_[p.a]++] = p;
  std::uint32_t begin = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t end = group_start_[i];         // now the end of group i
    for (std::uint32_t k = begin + 1; k < end; ++k) {  // insertion sort: groups are tiny
      const BodyPair p = out[k];
      std::uint32_t m = k;
      while (m > begin && out[m - 1].b > p.b) {
        out[m] = out[m - 1];
        --m;
      }
      out[m] = p;
    }
    begin = end;
  }
}

void UniformGrid::find_overlaps(const Aabb& query, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (columns_ > 0) {
    const double x0 = query.min.x - reach_;
    const double y0 = query.min.y - reach_;
    const double x1 = query.max.x + reach_;
    const double y1 = query.max.y + reach_;
    const double grid_max_x = origin_.x + cell_size_ * columns_;
    const double grid_max_y = origin_.y + cell_size_ * rows_;
    const bool misses_grid = x1 < origin_.x - cell_size_ || y1 < origin_.y - cell_size_ ||
                             x0 > grid_max_x || y0 > grid_max_y;
    if (!misses_grid) {
      const std::int32_t cx0 = cell_x(x0);
      const std::int32_t cx1 = cell_x(x1);
      for (std::int32_t y = cell_y(y0), y_end = cell_y(y1); y <= y_end; ++y) {
        const auto row = static_cast<std::uint32_t>(y * columns_);
        for (std::uint32_t k = cell_start_[row + cx0]; k < cell_start_[row + cx1 + 1]; ++k) {
          if (boxes_intersect(query, cell_boxes_[k])) out.push_back(cell_items_[k]);
        }
      }
    }
  }
  for (std::uint32_t j : large_) {
    if (boxes_intersect(query, boxes_[j])) out.push_back(j);
  }
  if (out.size() > 1) std::sort(out.begin(), out.end());
}

void UniformGrid::find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out) {
  build(boxes);
  find_pairs(out);
}

void UniformGrid::find_pairs_between(std::span<const Aabb> queries, std::span<const Aabb> targets,
                                     std::vector<BodyPair>& out) {
  build(targets);
  out.clear();
  std::vector<std::uint32_t> hits;
  for (std::uint32_t q = 0; q < queries.size(); ++q) {
    find_overlaps(queries[q], hits);
    for (std::uint32_t t : hits) out.push_back({q, t});
  }
}

}  // namespace phys
