#pragma once
// physics-sim --replay: checks a server recording and prints what it found.
#include <string>

namespace sim {

// Exit codes: 0 every recorded hash equal, 1 the replay diverged, 2 a bad file.
int replay_and_print(const std::string& path, bool json);

}  // namespace sim
