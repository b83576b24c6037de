// The client against a real physics-server over WebSocket: the handshake, the
// predicted encoding checked against the server's view hash on every snapshot, acks
// and the window, interest, byte budget, spectating, contact events, Ping, Bye.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import WebSocket from "ws";
import { Client, ConnectionState } from "../dist/index.js";
import { repoRoot } from "./doc.mjs";
import { startServer } from "./server.mjs";

const moving = `${repoRoot}scenes/moving-1000.textproto`;

function client(server, config = {}) {
  return new Client({ url: server.url, WebSocket, name: "node-test", ...config });
}

async function connected(server, config = {}) {
  const c = client(server, config);
  const ok = await c.connect(5000);
  assert.ok(ok, `connect: ${ConnectionState[c.state]}: ${c.lastError.detail}`);
  return c;
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

describe("lockstep on moving-1000", () => {
  let server;
  before(async () => {
    server = await startServer(["--scene", moving, "--lockstep", "--lockstep-pace", "asap"]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("600 ticks, the view hash equal on every snapshot", async () => {
    const c = await connected(server, { view: { viewHashInterval: 1 } });
    const welcome = c.welcome;
    assert.equal(welcome.sceneName, "moving-1000");
    assert.equal(welcome.lockstep, true);
    assert.equal(welcome.view.viewHashInterval, 1);
    let tick = welcome.currentTick;
    // The own body circles, so that its records are not all predicted away.
    const accel = (t) => [8 * Math.cos(t * 0.05), 8 * Math.sin(t * 0.05)];
    assert.ok(c.sendInput(tick + 1, ...accel(tick + 1)));
    let ownMoved = 0;
    let previous;
    for (let n = 0; n < 600; ++n) {
      const s = await c.nextSnapshot(5000);
      assert.ok(s, `snapshot ${n}: ${c.lastError.detail}`);
      assert.equal(s.tick, tick + 1, "lockstep sends every tick");
      tick = s.tick;
      assert.notEqual(s.viewHash, undefined, `snapshot of tick ${tick} carries no view hash`);
      assert.equal(c.viewHash(), s.viewHash, `view hash at tick ${tick}`);
      assert.ok(s.inSync);
      assert.equal(s.full, n === 0);
      assert.equal(s.bodies.length, 1001, "the 1,000 circles and the own body");
      if (previous && s.own && s.own.position.x !== previous.position.x) ++ownMoved;
      previous = s.own;
      c.sendInput(tick + 1, ...accel(tick + 1));
    }
    assert.equal(c.stats.viewHashesChecked, 600);
    assert.equal(c.stats.desyncs, 0);
    assert.equal(c.stats.acksSent, 600);
    assert.ok(ownMoved > 500, `the own body moved on ${ownMoved} ticks`);
    assert.ok(c.stats.recordsReceived < 600 * 1001, "records are sent only when a body leaves its prediction");
    c.disconnect();
    assert.equal(c.state, ConnectionState.Disconnected);
  });
});

describe("a fixed rate on the default scene", () => {
  let server;
  before(async () => {
    server = await startServer([]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("a player: inputs applied, the own body driven, the view hash equal", async () => {
    const c = await connected(server);
    assert.equal(c.welcome.spectator, false);
    assert.notEqual(c.welcome.bodyId, 0n);
    assert.ok(c.welcome.gravity.y < 0);
    const first = await c.nextSnapshot(5000);
    assert.ok(first.full);
    const start = first.own.position;
    let s = first;
    let sent = 0;
    while (s.tick < first.tick + 90) {
      if (c.sendInput(s.tick + 2, 20, 0)) ++sent;
      s = await c.nextSnapshot(5000);
      assert.ok(s, c.lastError.detail);
    }
    assert.ok(s.hasAppliedInput);
    assert.ok(s.lastAppliedInputTick > first.tick);
    assert.ok(s.own.position.x > start.x + 0.5, `the own body went from ${start.x} to ${s.own.position.x}`);
    assert.ok(c.stats.viewHashesChecked > 10);
    assert.equal(c.stats.desyncs, 0);
    assert.equal(c.stats.inputsSent, sent);
    c.disconnect();
  });

  test("Ping is answered with its nonce", async () => {
    const c = await connected(server, { spectate: true });
    assert.ok(c.sendPing(4242n, 77n));
    const pong = await c.nextPong(5000);
    assert.equal(pong.nonce, 4242n);
    assert.equal(pong.clientTimeNs, 77n);
    assert.ok(pong.serverTick >= c.welcome.currentTick);
    c.disconnect();
  });

  test("a spectator: no body, inputs refused without ending the session, contact events", async () => {
    const c = await connected(server, { spectate: true, contacts: { all: true } });
    assert.equal(c.welcome.spectator, true);
    assert.equal(c.welcome.bodyId, 0n);
    c.sendInput(c.welcome.currentTick + 1, 1, 0);
    const error = await c.nextError(5000);
    assert.equal(error.code, "SPECTATOR_INPUT");
    assert.equal(error.fatal, false);
    assert.equal(c.state, ConnectionState.Connected);
    const withEvents = await c.waitForSnapshot(10000, (s) => s.contactEvents.length > 0);
    assert.ok(withEvents, "no contact event in 10 s");
    const shapes = new Set(c.welcome.bodies.map((b) => b.bodyId));
    for (const e of withEvents.contactEvents) {
      assert.ok(e.tick <= withEvents.tick);
      assert.ok((e.bodyA & 0xffffffffn) < (e.bodyB & 0xffffffffn), "a's index below b's");
      assert.ok(shapes.has(e.bodyA) && shapes.has(e.bodyB));
      assert.ok(Math.abs(Math.hypot(e.normal.x, e.normal.y) - 1) < 1e-9, "a unit normal");
      assert.ok(Number.isFinite(e.closingSpeed));
    }
    assert.equal(withEvents.own, undefined);
    c.disconnect();
  });

  test("a player's radius of interest, its own contacts, a full state on request", async () => {
    const c = await connected(server, { view: { interestRadius: 3 }, contacts: {} });
    assert.equal(c.welcome.view.interestRadius, 3);
    const first = await c.nextSnapshot(5000);
    assert.ok(first.full);
    const all = c.welcome.bodies.filter((b) => !b.isStatic).length;
    let s = first;
    for (let n = 0; n < 30; ++n) {
      const own = s.own.position;
      for (const b of s.bodies) {
        // Within the radius, give or take the tolerance and a tick of motion.
        assert.ok(Math.hypot(b.position.x - own.x, b.position.y - own.y) < 3.5, `body ${b.bodyId} outside the radius`);
      }
      assert.ok(s.bodies.length < all, `${s.bodies.length} of ${all} dynamic bodies held`);
      for (const e of s.contactEvents) assert.ok(e.bodyA === c.welcome.bodyId || e.bodyB === c.welcome.bodyId);
      s = await c.nextSnapshot(5000);
      assert.ok(s);
    }
    const fullStates = c.stats.fullStatesReceived;
    assert.ok(c.requestFullState());
    const full = await c.waitForSnapshot(5000, (x) => x.full);
    assert.ok(full, "no full state after a FullStateRequest");
    assert.equal(c.stats.fullStatesReceived, fullStates + 1);
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });

  test("newestSnapshot drops the older snapshots and acknowledges the newest", async () => {
    const c = await connected(server, { spectate: true, view: { viewHashInterval: 1 } });
    await c.nextSnapshot(5000);
    for (let i = 0; i < 250 && c.bufferedSnapshots < 2; ++i) await sleep(20);
    assert.ok(c.bufferedSnapshots >= 2, "fewer than 2 snapshots in 5 s");
    const buffered = c.bufferedSnapshots;
    const acks = c.stats.acksSent;
    const newest = await c.newestSnapshot(5000);
    assert.ok(newest);
    assert.equal(c.bufferedSnapshots, 0);
    assert.equal(c.stats.acksSent, acks + 1, `one Ack for ${buffered} snapshots`);
    c.disconnect();
  });

  test("Bye removes the player's body: a spectator sees it in removed", async () => {
    const watcher = await connected(server, { spectate: true });
    const player = await connected(server);
    const id = player.welcome.bodyId;
    await watcher.waitForSnapshot(5000, (s) => s.added.some((b) => b.bodyId === id) || s.bodies.some((b) => b.bodyId === id));
    player.disconnect("done");
    assert.equal(player.state, ConnectionState.Disconnected);
    const gone = await watcher.waitForSnapshot(5000, (s) => s.removed.includes(id));
    assert.ok(gone, "the player's body was never removed");
    assert.equal(gone.bodies.find((b) => b.bodyId === id), undefined);
    watcher.disconnect();
  });
});

describe("views on moving-1000 at a fixed rate", () => {
  let server;
  before(async () => {
    server = await startServer(["--scene", moving]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("acks open the window: unacknowledged, the server sends no more than it", async () => {
    const c = await connected(server, { spectate: true, view: { window: 2 } });
    assert.equal(c.welcome.view.window, 2);
    for (let i = 0; i < 100 && c.stats.snapshotsReceived < 2; ++i) await sleep(20);
    assert.equal(c.stats.snapshotsReceived, 2);
    await sleep(300); // 18 ticks at 60 Hz, each with news
    assert.equal(c.stats.snapshotsReceived, 2, "a third snapshot came before any Ack");
    await c.nextSnapshot(0);
    await c.nextSnapshot(0);
    const third = await c.nextSnapshot(5000);
    assert.ok(third, "no snapshot after the Acks");
    assert.ok(c.stats.snapshotsReceived >= 3);
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });

  test("a rectangle of interest: only its bodies are held, and the hashes agree", async () => {
    const rect = { minX: 0, minY: 0, maxX: 50, maxY: 50 };
    const c = await connected(server, { spectate: true, view: { interestRect: rect, viewHashInterval: 1 } });
    assert.deepEqual(c.welcome.view.interestRect, rect);
    let s;
    // A snapshot comes when a body enters, leaves or leaves its prediction.
    for (let n = 0; n < 30; ++n) {
      s = await c.nextSnapshot(5000);
      assert.ok(s);
      assert.ok(s.bodies.length > 50 && s.bodies.length < 600, `${s.bodies.length} bodies held`);
      for (const b of s.bodies) {
        // Within the tolerance and one tick of motion of the rectangle's edges.
        assert.ok(b.position.x > -1 && b.position.y > -1, `body ${b.bodyId} at ${b.position.x}, ${b.position.y}`);
      }
    }
    assert.equal(c.stats.viewHashesChecked, 30);
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });

  test("a byte budget: the full state arrives over several snapshots", async () => {
    const c = await connected(server, { spectate: true, view: { byteBudget: 200 } });
    assert.equal(c.welcome.view.byteBudget, 200);
    const first = await c.nextSnapshot(5000);
    assert.ok(first.full);
    assert.ok(first.bodiesMissing > 900, `${first.bodiesMissing} missing at first`);
    assert.ok(first.wireBytes < 400, `${first.wireBytes} bytes`);
    const complete = await c.waitForSnapshot(20000, (s) => s.bodiesMissing === 0);
    assert.ok(complete, "never held every body");
    assert.equal(complete.bodies.length, 1000);
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });

  test("the exact and full encodings", async () => {
    for (const encoding of ["exact", "full"]) {
      const c = await connected(server, { spectate: true, view: { encoding, viewHashInterval: 1 } });
      assert.equal(c.welcome.view.encoding, encoding);
      for (let n = 0; n < 20; ++n) assert.ok(await c.nextSnapshot(5000));
      assert.equal(c.stats.desyncs, 0, encoding);
      assert.equal(c.stats.viewHashesChecked, 20, encoding);
      c.disconnect();
    }
  });
});
