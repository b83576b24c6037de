// The input clock driven by hand (src/input_clock.ts), the cases of the C++ client's
// tests/client/input_clock_test.cpp: the server's tick it estimates from snapshots,
// the tick it has inputs sent for, and the lead it adapts from the margins.
import { test } from "node:test";
import assert from "node:assert/strict";
import { InputClock } from "../dist/index.js";

const RATE = 60;
const PERIOD = 1000 / RATE;
const near = (actual, expected, tolerance, what) =>
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual}, expected ${expected} ± ${tolerance}`);

// A server stepping tick t at origin + t periods; snapshots reach the client `oneWay`
// ms later.
function path(oneWay = 50) {
  const p = { origin: 1_000_000, oneWay };
  p.stepped = (tick) => p.origin + PERIOD * tick;
  p.seen = (tick) => p.stepped(tick) + p.oneWay;
  return p;
}

test("the server's tick from snapshots and the round trip", () => {
  const clock = new InputClock({ tickRate: RATE });
  const p = path();
  clock.onRoundTrip(2 * p.oneWay, p.seen(0));
  for (let t = 1; t <= 30; ++t) clock.onTickSeen(t, p.seen(t));
  near(clock.serverTick(p.stepped(40)), 40, 1e-6, "at tick 40");
  // A late snapshot moves the estimate a sixteenth of its delay; one on time puts it back.
  clock.onTickSeen(31, p.seen(31) + 12);
  near(clock.serverTick(p.stepped(40)), 40 - 0.75 / PERIOD, 1e-6, "after a late snapshot");
  clock.onTickSeen(32, p.seen(32));
  near(clock.serverTick(p.stepped(40)), 40, 1e-6, "after one on time");
  // A server that fell 50 ms behind is followed: most of the way in 48 snapshots.
  p.origin += 50;
  for (let t = 33; t <= 80; ++t) clock.onTickSeen(t, p.seen(t));
  near(clock.serverTick(p.stepped(90)), 90, 0.2, "after the server fell behind");
});

test("the first lead is half the round trip plus the safety", () => {
  const clock = new InputClock({ tickRate: RATE, safetyMs: 2 });
  const p = path();
  clock.onRoundTrip(100, p.seen(0));
  near(clock.lead(), 52, 1e-9, "lead");
  assert.equal(clock.delay(), 4, "52 ms is 3.12 ticks, rounded up");
  for (let t = 1; t <= 10; ++t) clock.onTickSeen(t, p.seen(t));
  assert.equal(clock.sendUpTo(p.stepped(20)), 23);
  const next = clock.nextSendTime(p.stepped(20));
  assert.equal(clock.sendUpTo(next + 0.001), 24);
  assert.equal(clock.sendUpTo(next - 0.001), 23);
});

test("a late margin raises the lead once a round trip", () => {
  const clock = new InputClock({ tickRate: RATE, safetyMs: 2 });
  const p = path();
  clock.onRoundTrip(100, p.seen(0));
  const before = clock.lead();
  clock.onMargin(-5000, p.seen(10));
  near(clock.lead(), before + 7, 1e-9, "raised by the shortfall");
  assert.equal(clock.raises, 1);
  clock.onMargin(-5000, p.seen(12));
  assert.equal(clock.raises, 1, "margins within a round trip are of inputs sent before the raise");
  clock.onMargin(-1000, p.seen(10) + 100 + 3 * PERIOD);
  assert.equal(clock.raises, 2);
  near(clock.lead(), before + 10, 1e-9, "raised again");
});

test("spare margin lowers the lead slowly", () => {
  const clock = new InputClock({ tickRate: RATE, safetyMs: 2 });
  const p = path();
  clock.onRoundTrip(100, p.seen(0));
  const before = clock.lead();
  for (let t = 1; t <= 61; ++t) clock.onMargin(22000, p.seen(t));
  assert.equal(clock.lowers, 1);
  near(clock.lead(), before - 10, 1e-9, "half of 20 ms to spare given back");
  const steady = new InputClock({ tickRate: RATE, safetyMs: 2 });
  steady.onRoundTrip(100, p.seen(0));
  for (let t = 1; t <= 300; ++t) steady.onMargin(4000, p.seen(t));
  assert.equal(steady.lowers, 0, "within an eighth of a tick of the safety: kept");
  near(steady.lead(), before, 1e-9, "steady lead");
});

test("a fixed delay ignores margins, and the lead is capped", () => {
  const fixed = new InputClock({ tickRate: RATE, fixedDelay: 6 });
  const p = path();
  fixed.onRoundTrip(100, p.seen(0));
  fixed.onMargin(-50000, p.seen(5));
  assert.equal(fixed.delay(), 6);
  near(fixed.lead(), 6 * PERIOD, 1e-9, "fixed lead");
  const capped = new InputClock({ tickRate: RATE, maxDelay: 10 });
  capped.onRoundTrip(100, p.seen(0));
  capped.onMargin(-10_000_000, p.seen(5));
  assert.equal(capped.delay(), 10);
});

test("a waiting lockstep server stands still until a tick is seen", () => {
  const clock = new InputClock({ tickRate: RATE });
  clock.onWaitingAt(7);
  assert.equal(clock.serverTick(5000), 7);
  assert.equal(clock.serverTick(15000), 7);
  clock.onTickSeen(8, 5000);
  assert.ok(clock.serverTick(6000) > 60);
});
