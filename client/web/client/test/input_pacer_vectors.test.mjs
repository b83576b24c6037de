// The input pacer (src/input_pacer.ts) against tests/vectors/input_pacer.json, whose
// clock settings the C++ client's InputPacer checks too
// (tests/client/input_pacer_vectors_test.cpp), on a stand-in client with a clock of its
// own: no socket, no server, no waiting.
import { test } from "node:test";
import assert from "node:assert/strict";
import { ConnectionState, InputPacer, InputSchedule } from "../dist/index.js";
import { camel, loadVectors, near } from "./vectors.mjs";

const vectors = loadVectors("input_pacer");

// What InputPacer uses of a Client. Waiting for a snapshot moves its clock on to the
// snapshot's arrival or to the end of the wait; pongs are taken once they have arrived.
class StandInClient {
  constructor(welcome) {
    this.welcome = {
      tickRate: welcome.tick_rate,
      maxTicksAhead: welcome.max_ticks_ahead,
      currentTick: welcome.current_tick ?? 0,
      lockstep: welcome.lockstep ?? false,
    };
    this.state = ConnectionState.Connected;
    this.time = 0;
    this.pongs = [];
    this.snapshots = [];
    this.inputs = [];
  }
  now() {
    return this.time;
  }
  sendPing() {
    return true;
  }
  sendInput(tick) {
    this.inputs.push(tick);
    return true;
  }
  takePongs() {
    const arrived = this.pongs.filter((pong) => pong.receivedAt <= this.time);
    this.pongs = this.pongs.filter((pong) => pong.receivedAt > this.time);
    return arrived;
  }
  async nextSnapshot(timeoutMs) {
    const next = this.snapshots[0];
    if (next && next.receivedAt <= this.time + timeoutMs) {
      this.snapshots.shift();
      this.time = Math.max(this.time, next.receivedAt);
      return next;
    }
    this.time += timeoutMs;
    return undefined;
  }
}

const schedules = { clock: InputSchedule.Clock, "after-snapshot": InputSchedule.AfterSnapshot };

for (const vector of vectors.clock_from_welcome) {
  test(`clock from the Welcome: ${vector.name}`, () => {
    const client = new StandInClient({ ...vector.welcome, current_tick: 0, lockstep: true });
    const clock = { fixedDelay: vector.clock.fixed_delay };
    if (vector.clock.tick_rate !== undefined) clock.tickRate = vector.clock.tick_rate;
    if (vector.clock.max_delay !== undefined) clock.maxDelay = vector.clock.max_delay;
    const pacer = new InputPacer(client, { clock });
    near(pacer.clock.periodMs, vector.period_ms, 1e-9, "period");
    assert.equal(pacer.clock.delay(), vector.delay);
  });
}

for (const vector of vectors.schedules) {
  test(`schedule: ${vector.name}`, async () => {
    const client = new StandInClient(vector.welcome);
    const config = {};
    if (vector.config?.schedule) config.schedule = schedules[vector.config.schedule];
    const pacer = new InputPacer(client, config);
    for (const [index, step] of vector.steps.entries()) {
      const where = `step ${index} (${step.do ?? step.expect})`;
      if (step.do === "pong") {
        const sent = step.at_ms - step.round_trip_ms;
        client.pongs.push({ nonce: 1n, clientTimeNs: BigInt(sent * 1e6), serverTick: 0, receivedAt: step.at_ms });
      } else if (step.do === "snapshot") {
        client.snapshots.push({ tick: step.tick, bodies: [], receivedAt: step.at_ms });
      } else if (step.do === "poll") {
        while (client.now() < step.until_ms) await pacer.poll(step.until_ms, () => ({ ax: 0, ay: 0 }));
      } else if (step.expect === "stats") {
        for (const [key, value] of Object.entries(step)) {
          if (key === "expect") continue;
          assert.equal(pacer.stats[camel(key)], value, `${where}: ${key}`);
        }
      } else if (step.expect === "inputs_sent_at_least") {
        assert.ok(pacer.stats.inputsSent >= step.value, `${where}: ${pacer.stats.inputsSent} inputs`);
      } else if (step.expect === "last_sent") {
        assert.equal(pacer.lastSent, step.value, where);
      } else {
        assert.fail(`${where}: no such step`);
      }
    }
  });
}
