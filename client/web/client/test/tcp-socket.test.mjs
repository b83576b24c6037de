// bench/tcp-socket.mjs, the TCP transport bench/ws-vs-tcp.mjs compares the WebSocket
// port with: its framing against the bytes of docs/PROTOCOL.md 1.2 and against a
// stream cut anywhere, and the Client over it on the server's TCP port.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import { Client, ConnectionState } from "../dist/index.js";
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
