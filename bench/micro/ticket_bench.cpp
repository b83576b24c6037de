// The cost of admitting by connect ticket (docs/SERVER.md, "Connect tickets"): what
// the server pays per Hello to check a ticket (ticket::check: base64url, the key id
// and the seal, two HMAC-SHA-256), for a valid ticket, one with a changed byte and a
// missing one, and what a backend pays to mint one (ticket::mint).
#include <benchmark/benchmark.h>

#include <string>

#include "ticket/ticket.h"

namespace {

constexpr std::uint64_t kNow = 1'800'000'000;

ticket::Ticket bench_ticket() {
  ticket::Ticket t;
  t.player_id = 42;
  t.seat = 1;
  t.room = "goal-rush";
  t.expires_at = kNow + 3600;
  t.nonce = ticket::new_nonce();
  return t;
}

void BM_TicketCheckValid(benchmark::State& state) {
  const ticket::Key key = ticket::new_key();
  const std::string text = ticket::mint(bench_ticket(), key);
  for (auto _ : state) {
    benchmark::DoNotOptimize(ticket::check(text, key, kNow, "goal-rush"));
  }
}
BENCHMARK(BM_TicketCheckValid);

void BM_TicketCheckTampered(benchmark::State& state) {
  const ticket::Key key = ticket::new_key();
  std::string text = ticket::mint(bench_ticket(), key);
  text[30] = text[30] == 'A' ? 'B' : 'A';
  for (auto _ : state) {
    benchmark::DoNotOptimize(ticket::check(text, key, kNow, "goal-rush"));
  }
}
BENCHMARK(BM_TicketCheckTampered);

void BM_TicketCheckMissing(benchmark::State& state) {
  const ticket::Key key = ticket::new_key();
  for (auto _ : state) {
    benchmark::DoNotOptimize(ticket::check("", key, kNow, "goal-rush"));
  }
}
BENCHMARK(BM_TicketCheckMissing);

void BM_TicketMint(benchmark::State& state) {
  const ticket::Key key = ticket::new_key();
  const ticket::Ticket t = bench_ticket();
  for (auto _ : state) benchmark::DoNotOptimize(ticket::mint(t, key));
}
BENCHMARK(BM_TicketMint);

}  // namespace
