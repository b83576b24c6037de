#pragma once
// The world's bodies filed for its queries (physics/query.h), in three uniform grids:
// the static bodies' (made again only when a static body is added or removed), the
// sleeping bodies' (when a body falls asleep, wakes, or a sleeping one is removed)
// and the awake and kinematic bodies' (at the first query after a step or a change).
// A world whose bodies sleep thus files only what moves. A copy starts empty, so that
// a saved or restored world never answers from another world's grids.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "physics/broadphase.h"
#include "physics/vec2.h"

namespace phys {

struct Body;
struct BodyLists;

class QueryIndex {
 public:
  QueryIndex() = default;
  QueryIndex(const QueryIndex& /*other*/) {}
  QueryIndex& operator=(const QueryIndex& /*other*/) {
    forget_all();
    return *this;
  }
  QueryIndex(QueryIndex&&) noexcept = default;
  QueryIndex& operator=(QueryIndex&&) noexcept = default;
  ~QueryIndex() = default;

  // What changed: the awake or kinematic bodies (a step, one added, removed or moved),
  // the sleeping ones (one fell asleep, woke or was removed), the static ones.
  void forget_moving() { moving_.valid = false; }
  void forget_sleeping() { sleeping_.valid = false; }
  void forget_static() { static_.valid = false; }
  void forget_all() {
    forget_moving();
    forget_sleeping();
    forget_static();
  }
  // Files the bodies again where forgotten. `lists`, when not null, are the step's
  // lists as they stand (awake and kinematic bodies): the moving grid is then made
  // from them alone, not from a walk over every body.
  void refresh(std::span<const Body> bodies, const BodyLists* lists);

  // Slots of the bodies whose boxes overlap `box`, ascending, and some more: the box
  // is grown by a margin far wider than rounding, so that no body an exact test
  // finds is left out.
  void overlapping(const Aabb& box, std::vector<std::uint32_t>& out) const;

  // The bodies that a box of half size `reach` may meet moved from `origin` along
  // `translation`, chunk by chunk along the path (each chunk's slots ascending; a body
  // may come in several chunks). `visit` returns the lowest fraction hit so far: once
  // it is below the end of a chunk, no later chunk can do better and the walk stops.
  using ChunkVisit = std::function<double(std::span<const std::uint32_t>)>;
  void sweep(Vec2 origin, Vec2 translation, Vec2 reach, const ChunkVisit& visit) const;

 private:
  struct Part {
    std::vector<std::uint32_t> slots;
    std::vector<Aabb> boxes;
    Aabb bounds{};  // every box's
    UniformGrid grid;
    bool valid = false;
    void file(std::span<const Body> bodies);  // the boxes of `slots`, in their grid
  };
  void sweep_part(const Part& part, Vec2 origin, Vec2 translation, Vec2 reach, double margin,
                  double& best, const ChunkVisit& visit) const;

  Part static_;
  Part sleeping_;
  Part moving_;
  mutable std::vector<std::uint32_t> found_;
  mutable std::vector<std::uint32_t> chunk_;
};

}  // namespace phys
