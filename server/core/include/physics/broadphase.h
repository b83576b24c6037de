#pragma once
// Candidate pairs of overlapping boxes, in about O(N) for well-spread bodies: a
// uniform grid whose cell size follows the bodies' sizes, with large boxes kept
// apart. The pairs come out in an order fixed by the inputs alone (box index and
// cell order), never by hashing or pointer values.
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
  // Every pair i < j whose boxes overlap (touching counts). `out` is cleared first.
  void find_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out);
  // Every pair between a box of `queries` (first) and a box of `targets` (second).
  void find_pairs_between(std::span<const Aabb> queries, std::span<const Aabb> targets,
                          std::vector<BodyPair>& out);
  double cell_size() const { return cell_size_; }

 private:
  void build(std::span<const Aabb> boxes);
  template <typename Visit>
  void visit_candidates(const Aabb& box, Visit&& visit) const;

  double cell_size_ = 1.0;
  double inv_cell_ = 1.0;
  Vec2 origin_{};
  std::int32_t columns_ = 0;
  std::int32_t rows_ = 0;
  std::vector<std::uint32_t> cell_start_;  // columns*rows + 1 offsets into cell_items_
  std::vector<std::uint32_t> cell_items_;  // box indices, grouped by cell
  std::vector<std::uint32_t> large_;       // boxes too big for the grid
  std::vector<std::uint32_t> scratch_;
};

}  // namespace phys
