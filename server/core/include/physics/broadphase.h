#pragma once
// Candidate pairs of overlapping boxes, in about O(N) for well-spread bodies: a
// uniform grid as large as the largest ordinary box, each box filed in the one cell
// holding its centre, so two overlapping boxes sit in the same or adjacent cells.
// Boxes much larger than the median (floors, walls) are kept apart and tested
// against everything. The pairs come out in an order fixed by the inputs alone
// (box index), never by hashing or pointer values.
#include <cstdint>
#include <span>
#include <vector>

#include "physics/vec2.h"

namespace phys {

struct BodyPair {
  std::uint32_t a;  // a < b
  std::uint32_t b;
  constexpr bool operator==(const BodyPair&) const = default;
  constexpr auto operator<=>(const BodyPair&) const = default;
};

// Every overlapping pair (touching counts), by testing all of them: the reference.
void find_pairs_brute_force(std::span<const Aabb> boxes, std::vector<BodyPair>& out);

class UniformGrid {
 public:
  // Indexes `boxes` (copied), replacing what was indexed before.
  void build(std::span<const Aabb> boxes);
  // Every pair i < j of the indexed boxes that overlap (touching counts), sorted by
  // i, then j. `out` is cleared first.
  void find_pairs(std::vector<BodyPair>& out) const;
  // Indices of the indexed boxes that overlap `query` (touching counts), ascending.
  // `out` is cleared first.
  void find_overlaps(const Aabb& query, std::vector<std::uint32_t>& out) const;
  std::size_t size() const { return boxes_.size(); }
  double cell_size() const { return cell_size_; }
  // Heap bytes of the index (the boxes and the cells), for memory budgets.
  std::size_t state_bytes() const {
    return boxes_.capacity() * sizeof(Aabb) + cell_start_.capacity() * sizeof(std::uint32_t) +
           cell_items_.capacity() * sizeof(std::uint32_t) + cell_boxes_.capacity() * sizeof(Aabb);
  }

  // Conveniences: build, then pairs among `boxes`; or pairs (query index, target
  // index) between two sets, sorted by query then target.
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);
  void find_pairs_between(std::span<const Aabb> queries, std::span<const Aabb> targets,
                          std::vector<BodyPair>& out);

 private:
  std::int32_t cell_x(double x) const;
  std::int32_t cell_y(double y) const;

  std::vector<Aabb> boxes_;
  double cell_size_ = 1.0;
  double inv_cell_ = 1.0;
  double reach_ = 0.0;  // the largest half extent filed in cells
  Vec2 origin_{};
  std::int32_t columns_ = 0;
  std::int32_t rows_ = 0;
  std::vector<std::uint32_t> cell_start_;  // columns*rows + 1 offsets into cell_items_
  std::vector<std::uint32_t> cell_items_;  // box indices, grouped by cell, ascending
  std::vector<Aabb> cell_boxes_;           // the boxes in cell_items_ order (locality)
  mutable std::vector<BodyPair> unsorted_;
  mutable std::vector<std::uint32_t> group_start_;
  std::vector<std::uint32_t> cell_of_;  // per box: its cell, or UINT32_MAX if large
  std::vector<std::uint32_t> large_;    // boxes too big for the cells, ascending
  std::vector<double> extents_;
  std::vector<std::uint32_t> fill_;
};

}  // namespace phys
