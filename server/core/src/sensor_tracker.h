#pragma once
// Sensor events (physics/sensor_events.h): after each step, the pairs of a sensor
// and a visitor whose shapes overlap, found through the broadphase's grid, are
// merged with the last step's; begins and ends come out in pair order. Only a
// world with sensors (or with overlaps left to end) runs it.
#include <cstdint>
#include <vector>

#include "physics/broadphase.h"
#include "physics/sensor_events.h"

namespace phys {

class WorldImpl;

class SensorTracker {
 public:
  // This step's overlaps and events (step: the step count after it). Returns how
  // many events.
  std::size_t update(std::uint64_t step, const WorldImpl& world);
  // Nothing overlaps and the last step had no events: a world without sensors
  // need not call update.
  bool idle() const { return current_.empty() && events_.empty(); }
  // Whether every overlap held names slots below `slots` (World::from_bytes checks).
  bool slots_below(std::size_t slots) const {
    for (const Pair& p : current_) {
      if (p.sensor >= slots || p.visitor >= slots) return false;
    }
    return true;
  }

  const std::vector<SensorEvent>& events() const { return events_; }
  std::size_t overlap_count() const { return current_.size(); }

  // Walks what carries over between steps, for World::to_bytes and from_bytes
  // (world_bytes.cpp, the only user).
  template <class A>
  void state_fields(A& a);

 private:
  // A pair: sensor then visitor, each by slot and generation, ordered as written.
  struct Pair {
    std::uint32_t sensor;
    std::uint32_t sensor_generation;
    std::uint32_t visitor;
    std::uint32_t visitor_generation;
    bool operator<(const Pair& o) const {
      if (sensor != o.sensor) return sensor < o.sensor;
      if (sensor_generation != o.sensor_generation) return sensor_generation < o.sensor_generation;
      if (visitor != o.visitor) return visitor < o.visitor;
      return visitor_generation < o.visitor_generation;
    }
    bool operator==(const Pair&) const = default;
  };

  std::vector<Pair> current_;  // overlapping after the last step, in pair order
  std::vector<Pair> next_;     // update's scratch
  std::vector<SensorEvent> events_;
  // update's scratch: the sensors' and the visitors' boxes, the visitors' slots,
  // and the pairs of boxes that meet.
  UniformGrid grid_;
  std::vector<Aabb> sensor_boxes_;
  std::vector<Aabb> visitor_boxes_;
  std::vector<std::uint32_t> visitor_slots_;
  std::vector<std::uint32_t> overlaps_;
};

}  // namespace phys
