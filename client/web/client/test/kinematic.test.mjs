// Kinematic bodies through @physics/client against a real physics-server on
// scenes/rules-room.textproto: the Welcome's shapes say how each body moves, with
// its velocity and collision filter; the lift (0.5 m/s along x) is in every
// snapshot, said to be kinematic, moving at its velocity in the full encoding and
// held within the view hash in the predicted one.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import WebSocket from "ws";
import { Client, ConnectionState } from "../dist/index.js";
import { repoRoot } from "./doc.mjs";
import { startServer } from "./server.mjs";

const rulesRoom = `${repoRoot}scenes/rules-room.textproto`;

async function spectator(server, view) {
  const c = new Client({ url: server.url, WebSocket, name: "kinematic-test", spectate: true, view });
  const ok = await c.connect(5000);
  assert.ok(ok, `connect: ${ConnectionState[c.state]}: ${c.lastError.detail}`);
  return c;
}

const named = (welcome, name) => welcome.bodies.find((b) => b.name === name);

describe("kinematic bodies on rules-room", () => {
  let server;
  before(async () => {
    server = await startServer(["--scene", rulesRoom]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("the Welcome's shapes carry motion, velocity and filter", async () => {
    const c = await spectator(server, {});
    const lift = named(c.welcome, "lift");
    assert.equal(lift.motion, "kinematic");
    assert.deepEqual(lift.velocity, { x: 0.5, y: 0 });
    assert.equal(lift.contactFriction, 0.6);
    assert.equal(named(c.welcome, "ground").motion, "static");
    assert.deepEqual(named(c.welcome, "ghost ledge").filter, { categoryBits: 2, maskBits: 0xffffffff, group: 0 });
    const ghost = named(c.welcome, "ghost");
    assert.equal(ghost.motion, "dynamic");
    assert.deepEqual(ghost.filter, { categoryBits: 1, maskBits: 0xfffffffd, group: -1 });
    assert.equal(named(c.welcome, "goal").isSensor, true);
    c.disconnect();
  });

  test("the full encoding: the lift in every snapshot at its velocity", async () => {
    const c = await spectator(server, { encoding: "full" });
    const lift = named(c.welcome, "lift").bodyId;
    let previous;
    for (let n = 0; n < 30; ++n) {
      const s = await c.nextSnapshot(5000);
      assert.ok(s, `snapshot ${n}: ${c.lastError.detail}`);
      const held = s.bodies.find((b) => b.bodyId === lift);
      assert.ok(held, `no lift at tick ${s.tick}`);
      assert.equal(held.motion, "kinematic");
      assert.equal(held.velocity.x, 0.5);
      if (previous) {
        const moved = held.position.x - previous.x;
        assert.ok(Math.abs(moved - (0.5 * (s.tick - previous.tick)) / 60) < 1e-9, `moved ${moved} by tick ${s.tick}`);
      }
      previous = { x: held.position.x, tick: s.tick };
    }
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });

  test("the predicted encoding: the lift held, the view hash equal on every snapshot", async () => {
    const c = await spectator(server, { viewHashInterval: 1 });
    const lift = named(c.welcome, "lift").bodyId;
    for (let n = 0; n < 20; ++n) {
      const s = await c.nextSnapshot(5000);
      assert.ok(s, `snapshot ${n}: ${c.lastError.detail}`);
      const held = s.bodies.find((b) => b.bodyId === lift);
      assert.ok(held, `no lift at tick ${s.tick}`);
      assert.equal(held.motion, "kinematic");
      assert.equal(c.viewHash(), s.viewHash, `view hash at tick ${s.tick}`);
    }
    assert.equal(c.stats.viewHashesChecked, 20);
    assert.equal(c.stats.desyncs, 0);
    c.disconnect();
  });
});
