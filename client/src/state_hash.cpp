#include "client/state_hash.h"

#include <algorithm>
#include <bit>

namespace client {
namespace {

// FNV-1a over the bytes of 64-bit words, least significant byte first (5.11).
class ByteFnv {
 public:
  void mix(std::uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      h_ = (h_ ^ ((word >> (8 * i)) & 0xFFu)) * 0x100000001b3ull;
    }
  }
  void mix(double value) { mix(std::bit_cast<std::uint64_t>(value)); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

// The core's numbers for word 2 (phys::Shape and phys::Motion).
std::uint64_t shape_and_motion(const BodyShape& shape) {
  const std::uint64_t kind = shape.shape == ShapeType::Circle ? 0 : 1;
  std::uint64_t motion = 1;
  if (shape.motion == Motion::Static) motion = 0;
  if (shape.motion == Motion::Kinematic) motion = 2;
  return kind | (motion << 8);
}

std::uint32_t index_of(std::uint64_t id) { return static_cast<std::uint32_t>(id); }

}  // namespace

std::optional<std::uint64_t> state_hash(const std::vector<BodyShape>& shapes,
                                        const std::vector<BodyState>& held,
                                        const std::vector<KnownAcceleration>& known) {
  // The world hashes its bodies in slot order: an id's low 32 bits.
  std::vector<const BodyShape*> order;
  order.reserve(shapes.size());
  for (const BodyShape& s : shapes) order.push_back(&s);
  std::sort(order.begin(), order.end(), [](const BodyShape* a, const BodyShape* b) {
    return index_of(a->body_id) < index_of(b->body_id);
  });
  ByteFnv h;
  for (const BodyShape* shape : order) {
    Vec2 position = shape->position;
    Vec2 velocity;
    if (shape->motion != Motion::Static) {
      const auto it =
          std::lower_bound(held.begin(), held.end(), shape->body_id,
                           [](const BodyState& b, std::uint64_t id) { return b.body_id < id; });
      if (it == held.end() || it->body_id != shape->body_id) return std::nullopt;
      position = it->position;
      velocity = it->velocity;
    }
    Vec2 acceleration = shape->acceleration;
    for (const KnownAcceleration& k : known) {
      if (k.body_id == shape->body_id) acceleration = k.acceleration;
    }
    const Vec2 half = shape->box_half_size();
    h.mix(shape->body_id);
    h.mix(shape_and_motion(*shape));
    h.mix(position.x);
    h.mix(position.y);
    h.mix(velocity.x);
    h.mix(velocity.y);
    h.mix(acceleration.x);
    h.mix(acceleration.y);
    h.mix(half.x);
    h.mix(half.y);
    if (shape->filter != CollisionFilter{} || shape->is_sensor) {
      h.mix(static_cast<std::uint64_t>(shape->filter.category_bits) |
            (static_cast<std::uint64_t>(shape->filter.mask_bits) << 32));
      h.mix(static_cast<std::uint64_t>(static_cast<std::uint32_t>(shape->filter.group)) |
            (static_cast<std::uint64_t>(shape->is_sensor ? 1 : 0) << 32));
    }
  }
  return h.value();
}

}  // namespace client
