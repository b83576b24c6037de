#include "replay_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <variant>

#include "scene/scene.h"
#include "server/simulation.h"

namespace rtest {

TempFile::TempFile(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "test";
  path_ = std::filesystem::path(::testing::TempDir()) / (test + "." + name);
  std::filesystem::remove(path_);
}

TempFile::~TempFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

std::string TempFile::bytes() const {
  std::ifstream in(path_, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(std::filesystem::file_size(path_)), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

recording::LoadedRecording load_or_fail(const std::filesystem::path& path) {
  auto loaded = recording::load_recording(path);
  if (auto* error = std::get_if<recording::RecordingError>(&loaded)) {
    ADD_FAILURE() << path << ": " << error->to_string();
    return {};
  }
  return std::get<recording::LoadedRecording>(std::move(loaded));
}

std::size_t count_kind(const recording::LoadedRecording& loaded,
                       physics::recording::Record::KindCase kind) {
  std::size_t count = 0;
  for (const auto& record : loaded.records) count += record.kind_case() == kind ? 1 : 0;
  return count;
}

phys::Vec2 scripted_input(std::size_t k, std::uint64_t t, std::uint64_t hold) {
  // Within the default scene's maximum (50 m/s^2), so nothing is clamped.
  const double phase = static_cast<double>(t / hold) * 0.9 + static_cast<double>(k) * 1.7;
  const double magnitude = 4.0 + 3.0 * static_cast<double>(k);
  return {magnitude * std::cos(phase), magnitude * std::sin(phase) + 6.0};
}

std::vector<std::uint64_t> record_in_process(const std::filesystem::path& path, std::size_t clients,
                                             std::uint64_t ticks, server::RecordOptions options,
                                             std::shared_ptr<server::GameRules> rules) {
  server::Simulation simulation(scene::default_scene(), {}, std::move(rules));
  std::string error;
  auto recorder = server::TickRecorder::create(path, simulation.scene(), simulation.tick_rate(),
                                               simulation.max_ticks_ahead(), options, &error);
  if (!recorder) {
    ADD_FAILURE() << error;
    return {};
  }
  simulation.record_to(std::move(recorder));
  for (std::size_t k = 0; k < clients; ++k) {
    if (!simulation.join(static_cast<server::ClientId>(k + 1))) ADD_FAILURE() << "no spawn";
  }
  std::vector<std::uint64_t> hashes;
  for (std::uint64_t t = 1; t <= ticks; ++t) {
    for (std::size_t k = 0; k < clients; ++k) {
      simulation.submit_input(static_cast<server::ClientId>(k + 1), t, scripted_input(k, t));
    }
    simulation.step_tick();
    hashes.push_back(simulation.world().state_hash());
  }
  simulation.record_to(nullptr);  // flushes and closes the file
  return hashes;
}

}  // namespace rtest
