#include "relay/follow_relay.h"

#include <cmath>

namespace relay {
namespace {
phys::Vec2 vec(const physics::wire::Vec2& v) { return {v.x(), v.y()}; }
std::string id_text(std::uint64_t id) {
  const phys::BodyId body = phys::BodyId::from_packed(id);
  return std::to_string(body.index) + "/" + std::to_string(body.generation);
}
}  // namespace

phys::BodyDef body_def(const physics::wire::RelayBody& body) {
  phys::BodyDef def;
  def.shape = body.shape() == physics::wire::SHAPE_CIRCLE ? phys::Shape::Circle : phys::Shape::Box;
  def.motion = body.is_static()      ? phys::Motion::Static
               : body.is_kinematic() ? phys::Motion::Kinematic
                                     : phys::Motion::Dynamic;
  def.position = vec(body.position());
  def.velocity = vec(body.velocity());
  def.acceleration = vec(body.acceleration());
  def.radius = body.radius();
  def.half_extents = vec(body.half_extents());
  def.mass = body.mass();
  def.restitution = body.restitution();
  def.friction = vec(body.friction());
  def.contact_friction = body.contact_friction();
  if (body.has_category_bits()) def.filter.category_bits = body.category_bits();
  if (body.has_mask_bits()) def.filter.mask_bits = body.mask_bits();
  def.filter.group = body.group();
  def.is_sensor = body.is_sensor();
  def.name = body.name();
  return def;
}

namespace {

// One list of changes (RelayTick.changes, before_step or after_step), in order.
FollowResult apply_list(
    phys::World& world, std::uint64_t tick,
    const google::protobuf::RepeatedPtrField<physics::wire::RelayChange>& list) {
  FollowResult result;
  const auto fail = [&](FollowProblem problem, std::string detail) {
    result.problem = problem;
    result.detail = "tick " + std::to_string(tick) + ": " + std::move(detail);
    return result;
  };
  for (const physics::wire::RelayChange& change : list) {
    if (change.has_added()) {
      const std::uint64_t expected = change.added().body_id();
      if (world.contains(phys::BodyId::from_packed(expected))) {
        return fail(FollowProblem::BodyMismatch,
                    "adds body " + id_text(expected) + ", which the world holds already");
      }
      const phys::BodyId got = world.add_body(body_def(change.added()));
      if (got.packed() != expected) {
        return fail(FollowProblem::BodyMismatch,
                    "adds body " + id_text(expected) + "; the world gave it " +
                        (got.is_valid() ? id_text(got.packed()) : std::string("no id (refused)")));
      }
    } else if (change.has_set()) {
      const physics::wire::RelaySet& set = change.set();
      const phys::BodyId id = phys::BodyId::from_packed(set.body_id());
      const bool ok =
          (!set.has_position() || world.set_position(id, vec(set.position()))) &&
          (!set.has_velocity() || world.set_velocity(id, vec(set.velocity()))) &&
          (!set.has_acceleration() || world.set_acceleration(id, vec(set.acceleration())));
      if (!ok) {
        return fail(FollowProblem::BadInput, "moves body " + id_text(set.body_id()) +
                                                 ", which the world does not hold, or to a "
                                                 "value it refuses");
      }
    } else if (change.has_game_state()) {
      const std::string& bytes = change.game_state();
      std::size_t used = 0;
      std::string why = "bytes are left over after it";
      std::optional<phys::GameState> state = phys::GameState::read_bytes(
          std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), &used,
          &why);
      if (!state || used != bytes.size()) {
        return fail(FollowProblem::BadInput, "sends a game state that is not one: " + why);
      }
      world.game_state() = std::move(*state);
    } else if (!world.remove_body(phys::BodyId::from_packed(change.removed()))) {
      return fail(FollowProblem::BodyMismatch,
                  "removes body " + id_text(change.removed()) + ", which the world does not hold");
    }
  }
  return result;
}

}  // namespace

FollowResult apply_changes_and_inputs(phys::World& world, const physics::wire::RelayTick& tick) {
  FollowResult result = apply_list(world, tick.tick(), tick.changes());
  if (result.problem != FollowProblem::None) return result;
  for (const physics::wire::RelayInput& input : tick.inputs()) {
    if (!world.set_acceleration(phys::BodyId::from_packed(input.body_id()),
                                {input.ax(), input.ay()})) {
      result.problem = FollowProblem::BadInput;
      result.detail = "tick " + std::to_string(tick.tick()) + " sets the acceleration of body " +
                      id_text(input.body_id()) +
                      ", which the world does not hold as a dynamic body, or not to a finite value";
      return result;
    }
  }
  return apply_list(world, tick.tick(), tick.before_step());
}

FollowResult apply_after_step(phys::World& world, const physics::wire::RelayTick& tick) {
  return apply_list(world, tick.tick(), tick.after_step());
}

FollowResult follow(phys::World& world, const physics::wire::RelayTick& tick, double dt) {
  FollowResult result = apply_changes_and_inputs(world, tick);
  if (result.problem != FollowProblem::None) return result;
  world.step(dt);
  result = apply_after_step(world, tick);
  if (result.problem != FollowProblem::None) return result;
  if (tick.has_state_hash()) {
    result.hash_checked = true;
    if (world.state_hash() != tick.state_hash()) {
      result.problem = FollowProblem::HashMismatch;
      result.detail = "after tick " + std::to_string(tick.tick()) + " the world's hash differs";
    }
  }
  return result;
}

std::optional<phys::World> world_from(const std::string& bytes, std::string* error) {
  return phys::World::from_bytes(
      std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), error);
}

}  // namespace relay
