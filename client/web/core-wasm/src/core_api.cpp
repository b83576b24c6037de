// The core's C API for WebAssembly (index.mjs wraps it): a world from a flat world
// (portable/flat_world.h), steps, the bodies, inputs and the state hash. Nothing
// throws (the build has no exceptions); a refused world gives a null handle and
// pc_last_error() says why.
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "physics/world.h"
#include "portable/flat_world.h"

namespace {

struct Handle {
  phys::World world;
  double dt;
  std::vector<phys::BodyId> ids;  // in the flat world's order
  char hash_hex[17] = {};
};

std::string& last_error() {
  static std::string error;
  return error;
}

}  // namespace

extern "C" {

// A world from `count` doubles; null when they do not describe one.
Handle* pc_create(const double* values, std::uint32_t count) {
  auto flat = portable::unflatten({values, count});
  if (auto* error = std::get_if<std::string>(&flat)) {
    last_error() = std::move(*error);
    return nullptr;
  }
  const portable::FlatWorld& def = std::get<portable::FlatWorld>(flat);
  phys::World world(def.settings);
  std::vector<phys::BodyId> ids;
  ids.reserve(def.bodies.size());
  for (std::size_t i = 0; i < def.bodies.size(); ++i) {
    phys::BodyDefError error = phys::BodyDefError::None;
    const phys::BodyId id = world.add_body(def.bodies[i], &error);
    if (!id.is_valid()) {
      last_error() = "flat world: body " + std::to_string(i) +
                     " refused by the world: " + std::string(phys::describe(error));
      return nullptr;
    }
    ids.push_back(id);
  }
  return new Handle{std::move(world), def.dt, std::move(ids)};
}

const char* pc_last_error() { return last_error().c_str(); }

void pc_destroy(Handle* handle) { delete handle; }

// The scene's fixed step, 1 / tick rate.
double pc_dt(const Handle* handle) { return handle->dt; }

// `steps` steps of the scene's dt.
void pc_step(Handle* handle, std::uint32_t steps) {
  for (std::uint32_t i = 0; i < steps; ++i) handle->world.step(handle->dt);
}

std::uint32_t pc_body_count(const Handle* handle) {
  return static_cast<std::uint32_t>(handle->world.body_count());
}

// Per body, in id order, 8 doubles: its index (its place in the flat world), shape (0 circle,
// 1 box), position x, y, velocity x, y, awake (0/1), motion (0 static, 1 dynamic).
// Writes at most `capacity` bodies and returns how many it wrote.
std::uint32_t pc_read_bodies(const Handle* handle, double* out, std::uint32_t capacity) {
  std::uint32_t written = 0;
  handle->world.for_each_body([&](const phys::BodyState& b) {
    if (written >= capacity) return;
    double* row = out + 8 * static_cast<std::size_t>(written++);
    row[0] = static_cast<double>(b.id.index);
    row[1] = b.shape == phys::Shape::Circle ? 0.0 : 1.0;
    row[2] = b.position.x;
    row[3] = b.position.y;
    row[4] = b.velocity.x;
    row[5] = b.velocity.y;
    row[6] = b.awake ? 1.0 : 0.0;
    row[7] = b.motion == phys::Motion::Static ? 0.0 : 1.0;
  });
  return written;
}

// A client's input: body `index` (the flat world's order) accelerates by (ax, ay)
// until set again. 0 for an unknown index, a static body or a non-finite value.
int pc_set_acceleration(Handle* handle, std::uint32_t index, double ax, double ay) {
  if (index >= handle->ids.size()) return 0;
  return handle->world.set_acceleration(handle->ids[index], {ax, ay}) ? 1 : 0;
}

// World::state_hash as 16 hex digits, as physics-sim prints it.
const char* pc_state_hash(Handle* handle) {
  std::snprintf(handle->hash_hex, sizeof handle->hash_hex, "%016llx",
                static_cast<unsigned long long>(handle->world.state_hash()));
  return handle->hash_hex;
}

}  // extern "C"
