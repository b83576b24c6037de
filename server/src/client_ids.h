#pragma once
// Client ids are 32 bits on the wire (Welcome.client_id) and after 2^32 connections
// the counter wraps: the next id handed out skips 0 and every id still in use, so a
// new connection never takes the id of a live one.
#include <cstdint>

namespace server {

// Returns the first id at or after `next` that is neither 0 nor live, and moves
// `next` past it. `is_live(id)` says whether a session holds id. Fewer than 2^32 - 1
// ids can be live at once (each needs a socket), so the search ends.
template <typename IsLive>
std::uint32_t take_free_id(std::uint32_t& next, const IsLive& is_live) {
  for (;;) {
    const std::uint32_t id = next++;  // unsigned: wraps to 0 after the maximum
    if (id != 0 && !is_live(id)) return id;
  }
}

}  // namespace server
