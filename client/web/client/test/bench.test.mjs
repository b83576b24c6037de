// What bench/ws-vs-tcp.mjs stands on. bench/tcp-socket.mjs, the TCP transport: its
// framing against the bytes of docs/PROTOCOL.md 1.2 and against a stream cut
// anywhere, and the Client over it on the server's TCP port. bench/light-client.mjs:
// its hand-written messages against toBinary's, its reading of a snapshot's tick
// against fromBinary's, and a session on each port that outlasts the window (so its
// acks count) with an input every tick (so they parse).
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import { create, toBinary } from "@bufbuild/protobuf";
import WebSocket from "ws";
import { Client, ConnectionState, wire } from "../dist/index.js";
import { LightClient, encodeAck, encodeInput, snapshotTick } from "../bench/light-client.mjs";
import { FrameReader, TcpSocket, frame } from "../bench/tcp-socket.mjs";
import { payloadOf, repoRoot, wireBytesOnPage } from "./doc.mjs";
import { startServer } from "./server.mjs";

describe("framing", () => {
  test("the worked examples' frames, written and read back", () => {
    for (const first of ["09 0a 07", "0f 12 0d"]) {
      const onPage = wireBytesOnPage(first);
      const payload = payloadOf(onPage);
      assert.deepEqual(new Uint8Array(frame(payload)), onPage);
      assert.deepEqual(new FrameReader(1 << 20).feed(Buffer.from(onPage)).map((f) => new Uint8Array(f)), [payload]);
    }
  });

  test("a stream of frames cut at every byte, and at every pair of places", () => {
    // Lengths around the varint's steps: 0, 1, 127 (one byte), 128, 300 (two bytes).
    const payloads = [0, 1, 127, 128, 300].map((n) => Buffer.alloc(n, n & 0xff));
    const stream = Buffer.concat(payloads.map(frame));
    const expected = payloads.map((p) => new Uint8Array(p));
    for (let a = 0; a <= stream.length; a += 1) {
      for (let b = a; b <= stream.length; b += a % 7 === 0 ? 1 : 41) {
        const reader = new FrameReader(1 << 20);
        const got = [stream.subarray(0, a), stream.subarray(a, b), stream.subarray(b)].flatMap((chunk) =>
          reader.feed(chunk),
        );
        assert.deepEqual(
          got.map((f) => new Uint8Array(f)),
          expected,
          `cut at ${a} and ${b}`,
        );
      }
    }
  });

  test("a frame over the limit, and a varint over 10 bytes, are refused before their payload", () => {
    assert.throws(() => new FrameReader(300).feed(Buffer.from([0xad, 0x02])), /301 bytes over 300/);
    assert.throws(() => new FrameReader(1 << 20).feed(Buffer.alloc(11, 0x80)), /over 10 bytes/);
  });
});

describe("the light client's messages", () => {
  const client = (kind) => toBinary(wire.ClientMessageSchema, create(wire.ClientMessageSchema, { kind }));
  // Ticks and sequences across the varint's steps; accelerations with zeros (left out).
  const ticks = [0, 1, 127, 128, 16383, 16384, 2 ** 32 + 5, 2 ** 53 - 1];
  const accels = [0, -0, 1.5, -5, 4.999999999999999, Number.MIN_VALUE];

  test("Ack and Input: the bytes of toBinary", () => {
    for (const tick of ticks) {
      assert.deepEqual(encodeAck(tick), client({ case: "ack", value: create(wire.AckSchema, { tick: BigInt(tick) }) }));
      for (const ax of accels) {
        for (const ay of accels) {
          const sequence = ticks[(tick + 3) % ticks.length];
          const value = create(wire.InputSchema, { tick: BigInt(tick), ax, ay, sequence: BigInt(sequence) });
          assert.deepEqual(encodeInput(tick, ax, ay, sequence), client({ case: "input", value }), `${tick} ${ax} ${ay}`);
        }
      }
    }
  });

  test("a snapshot's tick, as fromBinary reads it; undefined for other messages", () => {
    const server = (kind) => toBinary(wire.ServerMessageSchema, create(wire.ServerMessageSchema, { kind }));
    for (const tick of ticks) {
      const snapshot = create(wire.SnapshotSchema, { tick: BigInt(tick), stateHash: 7n, removed: [3n] });
      assert.equal(snapshotTick(server({ case: "snapshot", value: snapshot })), tick);
    }
    // A snapshot long enough for a two-byte length.
    const long = create(wire.SnapshotSchema, { tick: 300n, removed: Array.from({ length: 200 }, (_, i) => BigInt(i)) });
    assert.equal(snapshotTick(server({ case: "snapshot", value: long })), 300);
    assert.equal(snapshotTick(server({ case: "pong", value: create(wire.PongSchema, { nonce: 1n }) })), undefined);
    assert.equal(snapshotTick(server({ case: "error", value: create(wire.ErrorSchema, { message: "x" }) })), undefined);
  });
});

describe("the light client on both ports", () => {
  let server;
  before(async () => {
    server = await startServer(["--scene", `${repoRoot}scenes/moving-1000.textproto`]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  for (const [name, url, Transport] of [
    ["TCP", () => `tcp://127.0.0.1:${server.port}`, TcpSocket],
    ["WebSocket", () => server.url, WebSocket],
  ]) {
    test(`${name}: 60 snapshots, an Ack and an Input for each`, async () => {
      const ticks = [];
      let done;
      const finished = new Promise((resolve) => {
        done = resolve;
      });
      const c = new LightClient({
        url: url(),
        WebSocket: Transport,
        name: "light",
        onSnapshot: (self, tick) => {
          ticks.push(tick);
          self.sendInput(tick + 1, 5, -5);
          if (ticks.length === 60) done();
        },
      });
      assert.ok(await c.connect(5000), c.detail);
      await Promise.race([finished, new Promise((resolve) => setTimeout(resolve, 10000))]);
      assert.equal(ticks.length, 60, `snapshots: ${c.detail}`);
      // More than the window of 12: the server took the acks.
      for (let i = 1; i < ticks.length; ++i) assert.ok(ticks[i] > ticks[i - 1]);
      assert.ok(c.connected, c.detail);
      assert.equal(c.stats.acksSent, 60);
      assert.equal(c.stats.inputsSent, 60);
      c.disconnect();
    });
  }
});

describe("the client over TCP on moving-1000", () => {
  let server;
  before(async () => {
    server = await startServer(["--scene", `${repoRoot}scenes/moving-1000.textproto`]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("joins, and 120 snapshots keep the view hash equal to the server's", async () => {
    const c = new Client({ url: `tcp://127.0.0.1:${server.port}`, WebSocket: TcpSocket, view: { viewHashInterval: 1 } });
    assert.ok(await c.connect(5000), `connect: ${ConnectionState[c.state]}: ${c.lastError.detail}`);
    assert.equal(c.welcome.sceneName, "moving-1000");
    for (let n = 0; n < 120; ++n) {
      const s = await c.nextSnapshot(5000);
      assert.ok(s, `snapshot ${n}: ${c.lastError.detail}`);
      c.sendInput(s.tick + 1, 5 * Math.cos(n / 10), 5 * Math.sin(n / 10));
    }
    assert.ok(c.stats.viewHashesChecked >= 120);
    assert.equal(c.stats.desyncs, 0);
    assert.equal(c.stats.inputsSent, 120);
    c.disconnect();
    assert.equal(c.state, ConnectionState.Disconnected);
  });
});
