#pragma once
// The relay follower under hostile input (docs/PROTOCOL.md 5.12): the RelayTicks a
// server sends a client with ENCODING_INPUTS, fed to relay::follow on a world and,
// in snapshots, to a predicting client's PredictionCore. Shared by the libFuzzer
// harness (relay_follow_fuzz.cpp) and the seeds' run in the ordinary build
// (tests/predicting/relay_follow_seeds_test.cpp), so that both run the same code.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace relay_fuzz {

// One input: byte 0 picks the client (bit 0: a player whose own body is the first
// player's, else a spectator; bits 1-2: 1 to 4 relayed ticks a snapshot), then
// length-delimited RelayTick messages (a varint byte count, then the bytes). Nothing
// in them is trusted: a bad tick is refused, counted and asked to be resent, never
// a crash. Aborts when an invariant breaks (the confirmed tick goes back, the
// prediction runs past its barrier).
void run_one(const std::uint8_t* data, std::size_t size);

// Inputs made from a world stepped as a server steps it (inputs changed, a body added
// and one removed, the state hash every few ticks): the committed seeds.
std::vector<std::string> make_seeds();

}  // namespace relay_fuzz
