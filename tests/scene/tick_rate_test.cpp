// A scene's tick rate is held to the one range of scene/scene.h, both ends included.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "scene/scene.h"
#include "scene_test_support.h"

namespace {

using scene::kMaxTickRate;
using scene::kMinTickRate;
using scene::testing::accepted;
using scene::testing::kSpawn;
using scene::testing::refused;

std::string scene_at(double rate) {
  char number[64];
  std::snprintf(number, sizeof number, "%.17g", rate);
  return "world { tick_rate: " + std::string(number) +
         " bounds { min { x: -10 y: -10 } max { x: 10 y: 10 } } }\n" + std::string(kSpawn);
}

TEST(SceneTickRate, BothEndsOfTheRangeAreAccepted) {
  EXPECT_EQ(accepted(scene_at(kMinTickRate)).tick_rate, kMinTickRate);
  EXPECT_EQ(accepted(scene_at(kMaxTickRate)).tick_rate, kMaxTickRate);
}

TEST(SceneTickRate, JustOutsideEitherEndIsRefusedNamingTheRange) {
  for (const double rate : {std::nextafter(kMinTickRate, 0.0), std::nextafter(kMaxTickRate, 1e9),
                            9.62876890084745e-310}) {
    SCOPED_TRACE(rate);
    const scene::SceneError error = refused(scene_at(rate));
    EXPECT_EQ(error.field, "world.tick_rate");
    EXPECT_NE(error.message.find("[0.001, 1000]"), std::string::npos) << error.to_string();
  }
}

}  // namespace
