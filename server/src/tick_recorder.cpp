#include "server/tick_recorder.h"

#include <utility>

#include "server/recorded_scene.h"

namespace server {
namespace {

// Pushed to the operating system this often, so that a server that is killed
// leaves a recording that replays up to a few seconds before the end.
constexpr std::uint64_t kFlushEveryTicks = 64;

}  // namespace

std::unique_ptr<TickRecorder> TickRecorder::create(const std::filesystem::path& path,
                                                   const scene::SceneDef& scene, double tick_rate,
                                                   std::uint64_t max_ticks_ahead,
                                                   RecordOptions options, std::string* error) {
  if (options.hash_every == 0) options.hash_every = 1;
  physics::recording::Header header;
  physics::recording::ServerRun& run = *header.mutable_server();
  *run.mutable_scene() = to_recorded(scene);
  run.set_tick_rate(tick_rate);
  run.set_max_ticks_ahead(max_ticks_ahead);
  run.set_lockstep(options.lockstep);
  run.set_hash_every(options.hash_every);
  run.set_body_hashes_every(options.body_hashes_every);
  std::unique_ptr<recording::RecordingWriter> writer =
      recording::RecordingWriter::create(path, header, error);
  if (!writer) return nullptr;
  return std::unique_ptr<TickRecorder>(new TickRecorder(std::move(writer), options));
}

TickRecorder::TickRecorder(std::unique_ptr<recording::RecordingWriter> writer,
                           RecordOptions options)
    : writer_(std::move(writer)), options_(options) {}

TickRecorder::~TickRecorder() { writer_->flush(); }

void TickRecorder::joined(std::uint64_t tick, ClientId client, phys::BodyId body,
                          std::optional<std::uint32_t> seat) {
  last_written_.erase(client);
  record_.Clear();
  physics::recording::Join& join = *record_.mutable_join();
  join.set_tick(tick);
  join.set_client(client);
  join.set_body(body.packed());
  if (seat) join.set_seat(*seat);
  writer_->append(record_);
}

void TickRecorder::left(std::uint64_t tick, ClientId client) {
  last_written_.erase(client);
  record_.Clear();
  physics::recording::Leave& leave = *record_.mutable_leave();
  leave.set_tick(tick);
  leave.set_client(client);
  writer_->append(record_);
}

void TickRecorder::game_message(std::uint64_t tick, ClientId client, const std::string& payload) {
  record_.Clear();
  physics::recording::GameMessage& message = *record_.mutable_game_message();
  message.set_tick(tick);
  message.set_client(client);
  message.set_payload(payload);
  writer_->append(record_);
}

void TickRecorder::applied(std::uint64_t tick, ClientId client, phys::Vec2 acceleration) {
  // Compared as exact values: the world holds an acceleration until it is set to a
  // different one, so an equal input changes nothing and need not be replayed.
  const auto [it, inserted] = last_written_.try_emplace(client, acceleration);
  if (!inserted) {
    if (it->second == acceleration) return;
    it->second = acceleration;
  }
  record_.Clear();
  physics::recording::Input& input = *record_.mutable_input();
  input.set_tick(tick);
  input.set_client(client);
  input.set_ax(acceleration.x);
  input.set_ay(acceleration.y);
  writer_->append(record_);
}

void TickRecorder::stepped(std::uint64_t tick, const phys::World& world) {
  const bool bodies = options_.body_hashes_every > 0 && tick % options_.body_hashes_every == 0;
  if (!bodies && tick % options_.hash_every != 0) return;
  record_.Clear();
  physics::recording::TickHash& hash = *record_.mutable_tick_hash();
  hash.set_tick(tick);
  hash.set_state_hash(world.state_hash());
  if (bodies) {
    world.for_each_body([&hash](const phys::BodyState& body) {
      if (body.motion != phys::Motion::Dynamic) return;
      hash.add_body_ids(body.id.packed());
      hash.add_body_hashes(body_hash(body));
    });
  }
  writer_->append(record_);
  if (tick % kFlushEveryTicks == 0) writer_->flush();
}

}  // namespace server
