// The input pacer (src/input_pacer.ts) through a real path: a lockstep server at its
// tick rate behind physics-netsim's 50 ms each way. Counts, never times: how many of
// the margins the server reports were late.
import { test } from "node:test";
import assert from "node:assert/strict";
import WebSocket from "ws";
import { Client, ConnectionState, InputPacer, InputSchedule } from "../dist/index.js";
import { startNetsim, startServer } from "./server.mjs";

// `margins` snapshots that carry the server's input margin, of one player in a
// lockstep lobby of one that steps at its tick rate, through 50 ms each way.
async function through100msRoundTrip(schedule, margins) {
  const server = await startServer(["--lockstep-players", "1", "--lockstep-pace", "realtime"]);
  const link = await startNetsim(server.wsPort, ["--latency-ms", "50"]);
  try {
    const client = new Client({ url: link.url, WebSocket, name: "paced" });
    assert.ok(await client.connect(5000), `connect: ${ConnectionState[client.state]}: ${client.lastError.detail}`);
    const pacer = new InputPacer(client, { schedule });
    const seen = [];
    let tick = client.welcome.currentTick;
    while (seen.length < margins) {
      const snapshot = await pacer.poll(client.now() + 5000, (t) => ({ ax: 4 * Math.cos(0.1 * t), ay: 0 }));
      assert.ok(snapshot, `no snapshot after tick ${tick}: ${ConnectionState[client.state]} ${client.lastError.detail}`);
      assert.equal(snapshot.tick, tick + 1, "lockstep steps every tick, in order");
      tick = snapshot.tick;
      if (snapshot.inputMarginUs !== undefined) seen.push(snapshot.inputMarginUs);
    }
    client.disconnect();
    return { margins: seen, pacer };
  } finally {
    await link.stop();
    assert.equal(await server.stop(), 0);
  }
}

test("paced inputs arrive before their ticks are due through a 100 ms round trip", async () => {
  const { margins, pacer } = await through100msRoundTrip(InputSchedule.Clock, 240);
  // The first second is the delay settling.
  const settled = margins.slice(60);
  const late = settled.filter((m) => m < 0).length;
  assert.ok(late <= settled.length / 10, `${late} of ${settled.length} inputs late after the first second`);
  // 50 ms each way at 60 Hz: 3 ticks one way, and a little margin on top.
  const delay = pacer.clock.delay();
  assert.ok(delay >= 3 && delay <= 6, `input delay ${delay} ticks`);
  assert.ok(pacer.stats.pingsSent > 0 && pacer.clock.roundTrip() >= 100, "the round trip was measured");
});

test("inputs sent after each snapshot arrive late: the server waits a round trip a tick", async () => {
  const { margins } = await through100msRoundTrip(InputSchedule.AfterSnapshot, 40);
  const late = margins.filter((m) => m < 0).length;
  assert.ok(late >= margins.length * 0.9, `only ${late} of ${margins.length} inputs late`);
});
