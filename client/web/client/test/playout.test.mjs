// The playout buffer on a fake clock: interpolation, extrapolation and its bound,
// the refusals, the reset over a gap, the steered delay.
import { test } from "node:test";
import assert from "node:assert/strict";
import { PlayoutBuffer } from "../dist/index.js";

function snapshot(tick, bodies) {
  return {
    tick,
    bodies: bodies.map(([id, x, vx]) => ({ bodyId: id, position: { x, y: 0 }, velocity: { x: vx, y: 0 } })),
  };
}

const close = (a, b, what) => assert.ok(Math.abs(a - b) < 1e-9, `${what}: ${a} against ${b}`);

test("empty, then interpolated between the two snapshots around the shown time", () => {
  const p = new PlayoutBuffer({ tickRate: 10 });
  assert.equal(p.stateAtServerTime(1).status, "empty");
  assert.equal(p.push(snapshot(10, [[1n, 0, 1]]), 5), "accepted");
  assert.equal(p.push(snapshot(11, [[1n, 0.1, 1]]), 5.1), "accepted");
  const frame = p.stateAtServerTime(1.05);
  assert.equal(frame.status, "interpolating");
  close(frame.bodies[0].position.x, 0.05, "halfway");
  assert.equal(frame.newestTick, 11);
  assert.equal(p.stateAtServerTime(0.5).status, "early");
});

test("past the newest: extrapolated at the body's velocity, at most maxExtrapolation, then held", () => {
  const p = new PlayoutBuffer({ tickRate: 10, maxExtrapolation: 0.25 });
  p.push(snapshot(10, [[1n, 0, 2]]), 0);
  let frame = p.stateAtServerTime(1.1);
  assert.equal(frame.status, "extrapolating");
  close(frame.bodies[0].position.x, 0.2, "0.1 s at 2 m/s");
  frame = p.stateAtServerTime(3);
  assert.equal(frame.status, "holding");
  close(frame.bodies[0].position.x, 0.5, "held at 0.25 s");
});

test("a gap of several send intervals: carried at its velocity, then interpolated over the last", () => {
  const p = new PlayoutBuffer({ tickRate: 10 });
  p.push(snapshot(10, [[1n, 0, 1]]), 0);
  p.push(snapshot(20, [[1n, 5, 0]]), 1);
  close(p.stateAtServerTime(1.5).bodies[0].position.x, 0.5, "carried");
  close(p.stateAtServerTime(1.95).bodies[0].position.x, 0.9 + (5 - 0.9) * 0.5, "interpolated in the last interval");
});

test("refusals: stale ticks, NaN states and times; a gap over maxGap resets", () => {
  const p = new PlayoutBuffer({ tickRate: 10, maxGap: 5 });
  p.push(snapshot(10, [[1n, 0, 0]]), 0);
  assert.equal(p.push(snapshot(10, [[1n, 0, 0]]), 0.1), "stale");
  assert.equal(p.push(snapshot(11, [[1n, NaN, 0]]), 0.1), "bad-state");
  assert.equal(p.push(snapshot(11, [[1n, 0, 0]]), Infinity), "bad-time");
  assert.equal(p.push(snapshot(100, [[1n, 0, 0]]), 9), "reset");
  assert.equal(p.size, 1);
  assert.deepEqual([p.stats.stale, p.stats.badState, p.stats.badTime, p.stats.resets], [1, 1, 1, 1]);
  assert.throws(() => new PlayoutBuffer({ capacity: 1 }), /capacity/);
});

test("the shown time trails the newest by the delay; a body the same in the two newest is still", () => {
  const p = new PlayoutBuffer({ tickRate: 60 });
  // Snapshots arrive 20 ms after their server time, without jitter.
  for (let tick = 60; tick <= 120; ++tick) p.push(snapshot(tick, [[1n, tick / 60, 1], [2n, 3, 0]]), tick / 60 + 0.02);
  close(p.offset, 0.02, "offset");
  close(p.jitter, 0, "jitter");
  close(p.delay(), 3 / 60, "three send intervals");
  const frame = p.stateAt(2 + 0.02);
  close(frame.serverTime, 2 - 3 / 60, "shown");
  close(frame.bodies[0].position.x, 2 - 3 / 60, "body 1 where it was then");
  assert.equal(frame.bodies[0].still, false);
  assert.equal(frame.bodies[1].still, true);
  // A frame later the shown time has moved by the frame's time.
  close(p.stateAt(2.02 + 1 / 60).serverTime, 2 - 2 / 60, "a frame later");
});
