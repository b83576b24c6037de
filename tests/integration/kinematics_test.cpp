// An input moves the client's own body the way the kinematics say: over a real
// socket, in lockstep so that every input lands on the tick it names.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "harness.h"
#include "reference.h"
#include "test_scenes.h"

namespace itest {
namespace {

// Position after n steps of dt from rest under constant acceleration a, for the
// integrator the scene uses (each is exact for its own recurrence).
double closed_form(phys::Integrator integrator, double x0, double a, double dt, int n) {
  const double steps = static_cast<double>(n);
  switch (integrator) {
    case phys::Integrator::Exact:
      return x0 + 0.5 * a * (steps * dt) * (steps * dt);
    case phys::Integrator::SemiImplicitEuler:  // x_n = x0 + a dt^2 n(n+1)/2
      return x0 + a * dt * dt * steps * (steps + 1.0) / 2.0;
    case phys::Integrator::ExplicitEuler:  // x_n = x0 + a dt^2 n(n-1)/2
      return x0 + a * dt * dt * steps * (steps - 1.0) / 2.0;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(Kinematics, InputMovesOwnBodyAsTheFormulasSay) {
  const scene::SceneDef scene = free_flight_scene(/*with_gravity=*/true);
  server::ServerConfig config = test_config(/*lockstep=*/true);
  config.lockstep_timeout = 10s;  // one client: every tick waits for our input only
  RunningServer server(config, scene);

  client::Client player(server.exact_client_config("kinematics"));
  ASSERT_TRUE(player.connect(3s)) << player.last_error().to_string();
  const client::Welcome welcome = player.welcome();
  ASSERT_TRUE(welcome.lockstep);
  EXPECT_DOUBLE_EQ(welcome.tick_rate, 60.0);

  ReferenceRun reference(scene);
  reference.advance_to(welcome.current_tick);
  ASSERT_EQ(reference.add_player(welcome), welcome.body_id);
  const auto start = reference.body(welcome.body_id);
  ASSERT_TRUE(start.has_value());

  constexpr double kAx = 3.0;
  constexpr double kAy = 2.0;
  constexpr int kTicks = 30;
  std::optional<client::Snapshot> last;
  for (int i = 1; i <= kTicks; ++i) {
    const std::uint64_t tick = welcome.current_tick + static_cast<std::uint64_t>(i);
    ASSERT_TRUE(player.send_input(tick, kAx, kAy));
    reference.set_input(welcome.body_id, kAx, kAy);  // as the server does, every tick
    last = player.next_snapshot(3s);
    ASSERT_TRUE(last.has_value()) << "no snapshot for tick " << tick << ": "
                                  << player.last_error().to_string();
    ASSERT_EQ(last->tick, tick);
    ASSERT_TRUE(last->has_applied_input);
    EXPECT_EQ(last->last_applied_input_tick, tick);
    EXPECT_EQ(last->state_hash, reference.step()) << "tick " << tick;
  }

  ASSERT_TRUE(last->own.has_value());
  const double dt = 1.0 / scene.tick_rate;
  const auto integrator = scene.world.integrator;
  const double gy = scene.world.gravity.y;
  EXPECT_NEAR(last->own->position.x, closed_form(integrator, start->position.x, kAx, dt, kTicks),
              1e-9);
  EXPECT_NEAR(last->own->position.y,
              closed_form(integrator, start->position.y, kAy + gy, dt, kTicks), 1e-9);
  // The body really moved (so the comparison is not trivially true).
  EXPECT_GT(last->own->position.x - start->position.x, 0.1);
  const auto reference_body = reference.body(welcome.body_id);
  ASSERT_TRUE(reference_body.has_value());
  EXPECT_EQ(last->own->position.x, reference_body->position.x);
  EXPECT_EQ(last->own->velocity.y, reference_body->velocity.y);
}

}  // namespace
}  // namespace itest
