// server::Simulation and the recorded scene hold tick rates to scene/scene.h's range,
// both ends included; 0 asks Simulation for the scene's own rate.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

#include "scene/scene.h"
#include "server/recorded_scene.h"
#include "server/simulation.h"
#include "test_scene.h"

namespace {

using scene::kMaxTickRate;
using scene::kMinTickRate;

TEST(TickRate, TheRangeIsTheOneTheDocsPromise) {
  EXPECT_EQ(kMinTickRate, 0.001);
  EXPECT_EQ(kMaxTickRate, 1000.0);
  EXPECT_EQ(scene::tick_rate_problem(60.0), "");
  EXPECT_EQ(scene::tick_rate_problem(std::nan("")),
            "tick rate must be in [0.001, 1000] ticks per second, got nan");
}

TEST(TickRate, SimulationStepsAtEitherEndOfTheRange) {
  for (const double rate : {kMinTickRate, kMaxTickRate}) {
    SCOPED_TRACE(rate);
    server::Simulation simulation(server_test::free_space_scene(), {rate, 10});
    EXPECT_EQ(simulation.tick_rate(), rate);
  }
}

TEST(TickRate, SimulationRefusesJustOutsideEitherEnd) {
  for (const double rate : {std::nextafter(kMinTickRate, 0.0), std::nextafter(kMaxTickRate, 1e9),
                            9.62876890084745e-310, -60.0, std::nan("")}) {
    SCOPED_TRACE(rate);
    try {
      server::Simulation simulation(server_test::free_space_scene(), {rate, 10});
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(std::string(error.what()).rfind("tick rate must be in [0.001, 1000]", 0), 0u)
          << error.what();
    }
  }
}

TEST(TickRate, ZeroTakesTheScenesRateWhichIsHeldToTheSameRange) {
  scene::SceneDef scene = server_test::free_space_scene();
  scene.tick_rate = kMaxTickRate;
  EXPECT_EQ(server::Simulation(scene, {0.0, 10}).tick_rate(), kMaxTickRate);
  scene.tick_rate = std::nextafter(kMaxTickRate, 1e9);
  EXPECT_THROW(server::Simulation(scene, {0.0, 10}), std::invalid_argument);
}

TEST(TickRate, ARecordedSceneIsHeldToTheSameRange) {
  scene::SceneDef scene = server_test::free_space_scene();
  for (const double rate : {kMinTickRate, kMaxTickRate}) {
    scene.tick_rate = rate;
    const auto back = server::from_recorded(server::to_recorded(scene));
    ASSERT_TRUE(std::holds_alternative<scene::SceneDef>(back)) << std::get<std::string>(back);
    EXPECT_EQ(std::get<scene::SceneDef>(back).tick_rate, rate);
  }
  for (const double rate : {std::nextafter(kMinTickRate, 0.0), std::nextafter(kMaxTickRate, 1e9)}) {
    scene.tick_rate = rate;
    const auto back = server::from_recorded(server::to_recorded(scene));
    ASSERT_TRUE(std::holds_alternative<std::string>(back));
    EXPECT_EQ(std::get<std::string>(back).rfind("scene.tick_rate: tick rate must be in", 0), 0u);
  }
}

}  // namespace
