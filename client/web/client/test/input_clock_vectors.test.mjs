// The input clock (src/input_clock.ts) against tests/vectors/input_clock.json, the cases
// the C++ client's InputClock runs too (tests/client/input_clock_vectors_test.cpp).
import { test } from "node:test";
import assert from "node:assert/strict";
import { InputClock, defaultInputClockConfig } from "../dist/index.js";
import { loadVectors, near } from "./vectors.mjs";

const vectors = loadVectors("input_clock");

test("the default config is the vectors'", () => {
  assert.equal(defaultInputClockConfig.safetyMs, vectors.defaults.safety_ms);
  assert.equal(defaultInputClockConfig.maxDelay, vectors.defaults.max_delay);
});

function clockFor(config) {
  const c = {};
  if (config.tick_rate !== undefined) c.tickRate = config.tick_rate;
  if (config.safety_ms !== undefined) c.safetyMs = config.safety_ms;
  if (config.max_delay !== undefined) c.maxDelay = config.max_delay;
  if (config.fixed_delay !== undefined) c.fixedDelay = config.fixed_delay;
  return new InputClock(c);
}

for (const vector of vectors.cases) {
  test(vector.name, () => {
    const clock = clockFor(vector.config);
    const path = { ...vector.path };
    // The server steps tick t at origin + t of the clock's own periods.
    const at = (time) => {
      const plus = time.plus_ms ?? 0;
      if (time.ms !== undefined) return time.ms + plus;
      if (time.stepped !== undefined) return path.origin_ms + time.stepped * clock.periodMs + plus;
      return path.origin_ms + time.seen * clock.periodMs + path.one_way_ms + plus;
    };
    vector.steps.forEach((step, index) => {
      const where = `step ${index} (${step.do ?? step.expect})`;
      switch (step.do) {
        case "round_trip":
          clock.onRoundTrip(step.ms, at(step.at));
          return;
        case "round_trips":
          for (let i = 0; i < step.count; ++i) clock.onRoundTrip(step.ms, at(step.at));
          return;
        case "tick_seen":
          clock.onTickSeen(step.tick, at(step.at));
          return;
        case "ticks_seen":
          for (let t = step.from; t <= step.to; ++t) clock.onTickSeen(t, at({ seen: t }));
          return;
        case "margin":
          clock.onMargin(step.us, at(step.at));
          return;
        case "margins":
          for (let t = step.from; t <= step.to; ++t) clock.onMargin(step.us, at({ seen: t }));
          return;
        case "waiting_at":
          clock.onWaitingAt(step.tick);
          return;
        case "server_falls_behind":
          path.origin_ms += step.ms;
          return;
        case undefined:
          break;
        default:
          assert.fail(`${where}: no such step`);
      }
      switch (step.expect) {
        case "server_tick":
          near(clock.serverTick(at(step.at)), step.value, step.tolerance, where);
          return;
        case "send_up_to":
          assert.equal(clock.sendUpTo(at(step.at)), step.value, where);
          return;
        case "next_send_time": {
          const next = clock.nextSendTime(at(step.from));
          near(next, at(step.value), step.tolerance, where);
          assert.equal(clock.sendUpTo(next - 0.001), step.send_up_to_before, `${where}: just before`);
          assert.equal(clock.sendUpTo(next + 0.001), step.send_up_to_after, `${where}: just after`);
          return;
        }
        case "lead_ms":
          near(clock.lead(), step.value, step.tolerance, where);
          return;
        case "round_trip_ms":
          near(clock.roundTrip(), step.value, step.tolerance, where);
          return;
        case "delay":
          assert.equal(clock.delay(), step.value, where);
          return;
        case "raises":
          assert.equal(clock.raises, step.value, where);
          return;
        case "lowers":
          assert.equal(clock.lowers, step.value, where);
          return;
        default:
          assert.fail(`${where}: no such expectation`);
      }
    });
  });
}
