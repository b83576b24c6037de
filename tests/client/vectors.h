#pragma once
// The test vectors the C++ and the TypeScript clients share (tests/vectors/*.json): one
// file per twin, inputs and expected outputs, read by both languages' tests.
// PHYSICS_TEST_VECTORS_DIR is the folder, given by CMake.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace vectors {

inline nlohmann::json load(const std::string& name) {
  const std::string path = std::string(PHYSICS_TEST_VECTORS_DIR) + "/" + name + ".json";
  std::ifstream in(path);
  if (!in) {
    ADD_FAILURE() << "cannot read " << path;
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(in);
}

// JSON has no NaN or infinity: the files write them as strings.
inline double number(const nlohmann::json& value) {
  if (value.is_string()) {
    const std::string text = value.get<std::string>();
    if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (text == "inf") return std::numeric_limits<double>::infinity();
    if (text == "-inf") return -std::numeric_limits<double>::infinity();
    ADD_FAILURE() << "not a number: " << text;
    return 0.0;
  }
  return value.get<double>();
}

// A step's name for failure messages: its index and what it does or expects.
inline std::string where(std::size_t index, const nlohmann::json& step) {
  return "step " + std::to_string(index) + " (" +
         step.value("do", step.value("expect", std::string("?"))) + ")";
}

}  // namespace vectors
