// The playout buffer (src/playout.ts) against tests/vectors/playout_buffer.json, the
// cases the C++ client's PlayoutBuffer runs too (tests/client/playout_vectors_test.cpp).
import { test } from "node:test";
import assert from "node:assert/strict";
import { PlayoutBuffer, defaultPlayoutSettings, validatePlayoutSettings } from "../dist/index.js";
import { camel, camelKeys, loadVectors, near, num } from "./vectors.mjs";

const vectors = loadVectors("playout_buffer");
const TOLERANCE = 1e-9;

test("the default settings are the vectors'", () => {
  assert.deepEqual(defaultPlayoutSettings(), camelKeys(vectors.defaults));
});

test("settings in range are accepted, out of range refused with their name", () => {
  for (const range of vectors.ranges) {
    const field = camel(range.field);
    for (const value of range.valid) {
      const settings = { ...defaultPlayoutSettings(), [field]: num(value) };
      assert.equal(validatePlayoutSettings(settings), "", `${field} = ${value}`);
    }
    for (const value of range.invalid) {
      const settings = { ...defaultPlayoutSettings(), [field]: num(value) };
      assert.match(validatePlayoutSettings(settings), new RegExp(`^${field} = `), `${field} = ${value}`);
    }
  }
});

const snapshotOf = (tick, bodies) => ({
  tick,
  bodies: bodies.map(([id, x, y, vx, vy]) => ({
    bodyId: BigInt(id),
    position: { x: num(x), y: num(y) },
    velocity: { x: num(vx), y: num(vy) },
    motion: "dynamic",
  })),
});

function checkFrame(frame, step, where) {
  assert.equal(frame.status, step.status, `${where}: status`);
  for (const key of ["server_time", "lag", "extrapolated"]) {
    if (step[key] !== undefined) near(frame[camel(key)], step[key], TOLERANCE, `${where}: ${key}`);
  }
  if (step.newest_tick !== undefined) assert.equal(frame.newestTick, step.newest_tick, `${where}: newest tick`);
  if (step.bodies === undefined) return;
  assert.equal(frame.bodies.length, step.bodies.length, `${where}: bodies`);
  step.bodies.forEach(([id, x, y, vx, vy], i) => {
    const body = frame.bodies[i];
    assert.equal(body.bodyId, BigInt(id), `${where}: body ${i}`);
    near(body.position.x, x, TOLERANCE, `${where}: body ${id} x`);
    near(body.position.y, y, TOLERANCE, `${where}: body ${id} y`);
    near(body.velocity.x, vx, TOLERANCE, `${where}: body ${id} vx`);
    near(body.velocity.y, vy, TOLERANCE, `${where}: body ${id} vy`);
    if (step.still !== undefined) assert.equal(body.still, step.still.includes(id), `${where}: body ${id} still`);
  });
}

for (const vector of vectors.cases) {
  test(vector.name, () => {
    const buffer = new PlayoutBuffer(camelKeys(vector.settings));
    const rate = buffer.settings.tickRate;
    vector.steps.forEach((step, index) => {
      const where = `step ${index} (${step.do ?? step.expect})`;
      switch (step.do) {
        case "push":
          assert.equal(buffer.push(snapshotOf(step.tick, step.bodies), num(step.arrival)), step.result, where);
          return;
        case "push_ticks":
          for (let tick = step.from; tick <= step.to; ++tick) {
            buffer.push(snapshotOf(tick, step.bodies), tick / rate + step.transit);
          }
          return;
        case undefined:
          break;
        default:
          assert.fail(`${where}: no such step`);
      }
      switch (step.expect) {
        case "at_server_time":
          checkFrame(buffer.stateAtServerTime(step.time), step, where);
          return;
        case "state_at":
          checkFrame(buffer.stateAt(step.now), step, where);
          return;
        case "size":
          assert.equal(buffer.size, step.value, where);
          return;
        case "delay":
          near(buffer.delay(), step.value, TOLERANCE, where);
          return;
        case "jitter":
          near(buffer.jitter, step.value, TOLERANCE, where);
          return;
        case "offset":
          near(buffer.offset, step.value, TOLERANCE, where);
          return;
        case "stats":
          for (const [key, value] of Object.entries(step)) {
            if (key !== "expect") assert.equal(buffer.stats[camel(key)], value, `${where}: ${key}`);
          }
          return;
        default:
          assert.fail(`${where}: no such expectation`);
      }
    });
  });
}
