// Writes the seed corpus of the fuzz harnesses from real messages, so that the
// fuzzers start from inputs that get past parsing:
//   make_fuzz_seeds OUT_DIR SCENES_DIR
// OUT_DIR/server_messages/ (connection records, see server_messages_fuzz.cpp),
// OUT_DIR/client/ (a server's byte stream: Welcome, Snapshots, Error, Pong),
// OUT_DIR/snapshot/ (setup doubles, then delimited Snapshots), OUT_DIR/scene/ (the
// small scene files of SCENES_DIR), OUT_DIR/replay/ (a server recording of a
// short run, as physics-server --record writes one), OUT_DIR/world_bytes/ (the bytes
// of the small worlds of world_seeds.h), OUT_DIR/relay_follow/ (relayed ticks,
// relay_follow_target.h).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "recording/recording_file.h"
#include "relay_follow_target.h"
#include "scene/scene.h"
#include "server/recorded_scene.h"
#include "server/simulation.h"
#include "snapshot_encoder.h"
#include "snapshot_feeds.h"
#include "truth_frame.h"
#include "wire.pb.h"
#include "wire/framing.h"
#include "wire/messages.h"
#include "wire/view_settings.h"
#include "world_seeds.h"

namespace fs = std::filesystem;

namespace {

void write_file(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

// One record of server_messages_fuzz: [control][length, 2 bytes LE][bytes].
void add_record(std::string& out, std::uint8_t slot, std::uint8_t ticks, bool disconnect,
                const std::string& bytes) {
  out += static_cast<char>(slot | (disconnect ? 4 : 0) | (ticks << 3));
  out += static_cast<char>(bytes.size() & 0xff);
  out += static_cast<char>((bytes.size() >> 8) & 0xff);
  out += bytes;
}

physics::wire::ClientMessage hello_with(const std::string& token, bool spectate,
                                        physics::wire::Encoding encoding) {
  physics::wire::ClientMessage message = wire::make_hello("seed", token);
  message.mutable_hello()->set_spectate(spectate);
  message.mutable_hello()->mutable_view()->set_encoding(encoding);
  return message;
}

std::string frame_of(const physics::wire::ClientMessage& message) {
  return wire::encode_frame(message);
}

std::string ack(std::uint64_t tick) { return frame_of(wire::make_ack(tick)); }

void server_seeds(const fs::path& dir) {
  // Fixed rate: a player sends inputs and acks over ticks, pings, asks for a full
  // state and says bye; a second connection sends an Input before Hello.
  {
    std::string seed(1, '\0');
    add_record(seed, 0, 1, false,
               frame_of(hello_with("", false, physics::wire::ENCODING_PREDICTED)));
    for (std::uint64_t tick = 1; tick <= 4; ++tick) {
      add_record(seed, 0, 1, false,
                 frame_of(wire::make_input(tick + 1, 3.0, -2.0, tick)) + ack(tick));
    }
    const std::string full = frame_of(wire::make_full_state_request());
    add_record(seed, 0, 2, false, frame_of(wire::make_ping(7)) + full + full);
    add_record(seed, 1, 0, false, frame_of(wire::make_input(9, 1.0, 1.0)));
    add_record(seed, 0, 1, false, frame_of(wire::make_bye("done")));
    write_file(dir / "fixed_rate_player", seed);
  }
  // Lockstep, two players and a spectator with an area of interest; one player
  // disconnects while the other waits.
  {
    std::string seed(1, '\1');
    add_record(seed, 0, 0, false, frame_of(hello_with("", false, physics::wire::ENCODING_EXACT)));
    add_record(seed, 1, 0, false,
               frame_of(hello_with("", false, physics::wire::ENCODING_PREDICTED)));
    physics::wire::ClientMessage watch = hello_with("", true, physics::wire::ENCODING_FULL);
    physics::wire::Rect* rect = watch.mutable_hello()->mutable_view()->mutable_interest_rect();
    rect->set_min_x(-5);
    rect->set_min_y(-1);
    rect->set_max_x(5);
    rect->set_max_y(5);
    add_record(seed, 2, 0, false, frame_of(watch));
    for (std::uint64_t tick = 1; tick <= 3; ++tick) {
      add_record(seed, 0, 0, false, frame_of(wire::make_input(tick, 0.0, 5.0)));
      add_record(seed, 1, 1, false, frame_of(wire::make_input(tick, -1.0, 0.0)) + ack(tick));
    }
    add_record(seed, 1, 4, true, "");
    add_record(seed, 0, 3, false, frame_of(wire::make_input(4, 0.0, 0.0)));
    write_file(dir / "lockstep_two_players_and_a_spectator", seed);
  }
  // A token server: a wrong token, then the right one; a Hello cut into pieces.
  {
    std::string seed(1, '\2');
    add_record(seed, 0, 0, false,
               frame_of(hello_with("wrong", false, physics::wire::ENCODING_PREDICTED)));
    const std::string right =
        frame_of(hello_with("fuzz-token", false, physics::wire::ENCODING_PREDICTED));
    add_record(seed, 1, 0, false, right.substr(0, 5));
    add_record(seed, 1, 2, false, right.substr(5));
    add_record(seed, 1, 1, false, frame_of(wire::make_input(100000, 1e300, 0.0)));
    write_file(dir / "token", seed);
  }
}

// The byte stream a client gets from the real snapshot feeds after a Welcome.
std::string server_stream(physics::wire::Encoding encoding, int ticks) {
  const scene::SceneDef& scene = scene::default_scene();
  server::Simulation simulation(scene);
  server::SnapshotFeeds feeds(
      wire::Predictor(simulation.tick_rate(), simulation.world().settings().gravity.x,
                      simulation.world().settings().gravity.y),
      30, false);
  physics::wire::ViewRequest request;
  request.set_encoding(encoding);
  request.set_state_hash(true);
  wire::ViewSettings view;
  if (!wire::resolve_view(request, 64, view).empty()) std::exit(1);
  const auto body = simulation.join(1);
  if (!body) std::exit(1);
  feeds.join(1, view, body->packed());
  std::string out =
      wire::encode_frame(server::make_welcome(simulation, 1, *body, false, wire::to_wire(view), 8));
  server::TruthFrame previous;
  for (int i = 0; i < ticks; ++i) {
    simulation.submit_input(1, simulation.current_tick() + 1, {i % 2 == 0 ? 20.0 : -20.0, 5.0});
    const server::TickResult result = simulation.step_tick();
    const server::BodyChanges changes = simulation.take_changes();
    for (const phys::BodyId id : changes.added) feeds.note_added(id.packed());
    for (const std::uint64_t id : changes.removed) feeds.note_removed(id);
    server::TruthFrame frame = server::read_truth(simulation.world(), result.tick, &previous);
    for (const server::FeedOutput& o :
         feeds.after_tick(frame, simulation.world(), [](auto) { return server::ClientFields{}; })) {
      const std::string shared = o.shared ? *o.shared : std::string();
      out += server::snapshot_frame_header(shared.size() + o.tail.size()) + shared + o.tail;
      feeds.ack(1, o.tick);
    }
    previous = std::move(frame);
  }
  return out;
}

void client_seeds(const fs::path& dir) {
  write_file(dir / "predicted", server_stream(physics::wire::ENCODING_PREDICTED, 6));
  write_file(dir / "exact", server_stream(physics::wire::ENCODING_EXACT, 4));
  write_file(dir / "full", server_stream(physics::wire::ENCODING_FULL, 3));
  physics::wire::ServerMessage pong;
  pong.mutable_pong()->set_nonce(1);
  pong.mutable_pong()->set_server_tick(5);
  write_file(dir / "welcome_pong_error",
             server_stream(physics::wire::ENCODING_PREDICTED, 1) + wire::encode_frame(pong) +
                 wire::encode_frame(wire::make_error(physics::wire::ERROR_TOO_SLOW, "slow", true)));
  write_file(dir / "refused",
             wire::encode_frame(wire::make_error(physics::wire::ERROR_BAD_TOKEN, "no", true)));
}

// The snapshots of a client stream, without the Welcome, as snapshot_fuzz reads them.
void snapshot_seeds(const fs::path& dir) {
  for (const auto& [name, encoding] : {std::pair{"predicted", physics::wire::ENCODING_PREDICTED},
                                       std::pair{"exact", physics::wire::ENCODING_EXACT}}) {
    const std::string stream = server_stream(encoding, 6);
    std::string seed;
    const double setup[5] = {60.0, 0.0, -10.0, 0.001, 0.001};
    seed.append(reinterpret_cast<const char*>(setup), sizeof setup);
    wire::FrameReader reader;
    reader.feed(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(stream.data()),
                                              stream.size()));
    std::string frame;
    while (reader.next(frame) == wire::FrameStatus::Frame) {
      physics::wire::ServerMessage message;
      if (!message.ParseFromString(frame) || !message.has_snapshot()) continue;
      seed += wire::encode_frame(message.snapshot());
    }
    write_file(dir / name, seed);
  }
}

void scene_seeds(const fs::path& dir, const fs::path& scenes) {
  for (const char* name : {"default", "platformer", "box-pyramid", "circle-pile"}) {
    std::ifstream in(scenes / (std::string(name) + ".textproto"), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.empty()) {
      std::fprintf(stderr, "cannot read scene %s\n", name);
      std::exit(1);
    }
    write_file(dir / name, text);
  }
}

// A short server run as a recording: a join, inputs and every tick's hash, taken
// from a Simulation of the default scene.
void replay_seeds(const fs::path& dir) {
  const scene::SceneDef& scene = scene::default_scene();
  server::Simulation simulation(scene);
  physics::recording::Header header;
  physics::recording::ServerRun& run = *header.mutable_server();
  *run.mutable_scene() = server::to_recorded(scene);
  run.set_tick_rate(simulation.tick_rate());
  run.set_max_ticks_ahead(simulation.max_ticks_ahead());
  run.set_hash_every(1);
  std::vector<physics::recording::Record> records;
  const auto body = simulation.join(1);
  if (!body) std::exit(1);
  physics::recording::Join& join = *records.emplace_back().mutable_join();
  join.set_tick(0);
  join.set_client(1);
  join.set_body(body->packed());
  for (std::uint64_t tick = 1; tick <= 8; ++tick) {
    const double ax = tick % 2 == 0 ? 10.0 : -10.0;
    simulation.submit_input(1, tick, {ax, 2.0});
    physics::recording::Input& input = *records.emplace_back().mutable_input();
    input.set_tick(tick);
    input.set_client(1);
    input.set_ax(ax);
    input.set_ay(2.0);
    simulation.step_tick();
    physics::recording::TickHash& hash = *records.emplace_back().mutable_tick_hash();
    hash.set_tick(tick);
    hash.set_state_hash(simulation.world().state_hash());
  }
  physics::recording::Leave& leave = *records.emplace_back().mutable_leave();
  leave.set_tick(8);
  leave.set_client(1);
  write_file(dir / "join_inputs_hashes_leave", recording::encode_recording(header, records));
  write_file(dir / "header_only", recording::encode_recording(header, {}));
}

void world_bytes_seeds(const fs::path& dir) {
  for (const auto& [name, bytes] : fuzz_seeds::world_seeds()) {
    write_file(dir / name, std::string(bytes.begin(), bytes.end()));
  }
}

void relay_follow_seeds(const fs::path& dir) {
  const std::vector<std::string> seeds = relay_fuzz::make_seeds();
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    write_file(dir / ("relay_" + std::to_string(i)), seeds[i]);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_fuzz_seeds OUT_DIR SCENES_DIR\n");
    return 2;
  }
  const fs::path out = argv[1];
  server_seeds(out / "server_messages");
  client_seeds(out / "client");
  snapshot_seeds(out / "snapshot");
  scene_seeds(out / "scene", argv[2]);
  replay_seeds(out / "replay");
  world_bytes_seeds(out / "world_bytes");
  relay_follow_seeds(out / "relay_follow");
  return 0;
}
