// Bad input, both ways. The server's answers over WebSocket (docs/PROTOCOL.md 1.3: a
// fatal Error, then a close frame whose code says why), and the client's own
// refusals of what a server must never send (a fake socket plays the server).
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import WebSocket from "ws";
import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import { Client, ConnectionState, wire } from "../dist/index.js";
import { startServer } from "./server.mjs";

/** A raw WebSocket: what it received, and its close code. */
function rawSocket(url) {
  const socket = new WebSocket(url);
  socket.binaryType = "arraybuffer";
  const received = [];
  socket.on("message", (data, isBinary) => received.push(isBinary ? fromBinary(wire.ServerMessageSchema, new Uint8Array(data)) : String(data)));
  const closed = new Promise((resolve) => socket.on("close", (code) => resolve(code)));
  const opened = new Promise((resolve, reject) => {
    socket.on("open", resolve);
    socket.on("error", reject);
  });
  return { socket, received, closed, opened };
}

function fatalError(received) {
  const errors = received.filter((m) => typeof m !== "string" && m.kind.case === "error").map((m) => m.kind.value);
  assert.equal(errors.length, 1, `one Error, got ${JSON.stringify(received, (k, v) => (typeof v === "bigint" ? String(v) : v))}`);
  assert.equal(errors[0].fatal, true);
  return wire.ErrorCode[errors[0].code];
}

describe("the server's refusals over WebSocket", () => {
  let server;
  before(async () => {
    server = await startServer([]);
  });
  after(async () => assert.equal(await server.stop(), 0));

  test("a wrong protocol version: Refused, ERROR_PROTOCOL_VERSION naming both versions", async () => {
    // 3: the version before clients could run the game's rules.
    const c = new Client({ url: server.url, WebSocket, protocolVersion: 3 });
    assert.equal(await c.connect(5000), false);
    assert.equal(c.state, ConnectionState.Refused);
    assert.equal(c.lastError.server.code, "PROTOCOL_VERSION");
    assert.equal(c.lastError.server.fatal, true);
    assert.match(c.lastError.server.message, /version 3/);
    assert.match(c.lastError.server.message, /version 4/);
    assert.equal(c.welcome, undefined);
  });

  test("a truncated Hello: ERROR_MALFORMED, then close 1000", async () => {
    const { socket, received, closed, opened } = rawSocket(server.url);
    await opened;
    // The Hello of docs/PROTOCOL.md 1.2 without its length prefix, cut after 7 of its 9 bytes.
    socket.send(Uint8Array.from([0x0a, 0x07, 0x08, 0x02, 0x12, 0x03, 0x61]));
    assert.equal(await closed, 1000);
    assert.equal(fatalError(received), "ERROR_MALFORMED");
  });

  test("the Hello of PROTOCOL.md 1.2 with its TCP length prefix: ERROR_MALFORMED (no prefix on WebSocket)", async () => {
    const { socket, received, closed, opened } = rawSocket(server.url);
    await opened;
    socket.send(Uint8Array.from([0x09, 0x0a, 0x07, 0x08, 0x02, 0x12, 0x03, 0x61, 0x6e, 0x6e]));
    assert.equal(await closed, 1000);
    assert.equal(fatalError(received), "ERROR_MALFORMED");
  });

  test("a text message: ERROR_MALFORMED, then close 1003", async () => {
    const { socket, received, closed, opened } = rawSocket(server.url);
    await opened;
    socket.send("hello");
    assert.equal(await closed, 1003);
    assert.equal(fatalError(received), "ERROR_MALFORMED");
  });

  test("a truncated Input after Welcome ends the session: ConnectionLost, ERROR_MALFORMED", async () => {
    const c = new Client({ url: server.url, WebSocket });
    assert.ok(await c.connect(5000));
    const input = toBinary(
      wire.ClientMessageSchema,
      create(wire.ClientMessageSchema, { kind: { case: "input", value: { tick: 100n, ax: 1.5 } } }),
    );
    assert.ok(c.sendRaw(input.subarray(0, input.length - 3)));
    const error = await c.nextError(5000);
    assert.equal(error.code, "MALFORMED");
    assert.equal(error.fatal, true);
    assert.equal(c.state, ConnectionState.ConnectionLost);
    assert.equal(c.lastError.server.code, "MALFORMED");
  });

  test("nothing listening: ConnectFailed", async () => {
    const c = new Client({ url: "ws://127.0.0.1:1/", WebSocket });
    assert.equal(await c.connect(5000), false);
    assert.equal(c.state, ConnectionState.ConnectFailed);
  });
});

/** A socket whose server is the test: it sends what the test gives it. */
class FakeSocket {
  static last;
  binaryType = "";
  readyState = 0;
  onopen = null;
  onmessage = null;
  onclose = null;
  onerror = null;
  sent = [];
  constructor(url) {
    this.url = url;
    FakeSocket.last = this;
    queueMicrotask(() => {
      this.readyState = 1;
      this.onopen?.({});
    });
  }
  send(bytes) {
    this.sent.push(fromBinary(wire.ClientMessageSchema, bytes));
  }
  close() {
    this.readyState = 3;
  }
  deliver(data) {
    this.onmessage?.({ data });
  }
}

function serverMessage(kind) {
  const bytes = toBinary(wire.ServerMessageSchema, create(wire.ServerMessageSchema, { kind }));
  return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length);
}

const welcome = { case: "welcome", value: { protocolVersion: 4, tickRate: 60, bodyId: 5n, currentTick: 10n } };

async function fakeSession(first, config = {}) {
  const c = new Client({ url: "ws://fake/", WebSocket: FakeSocket, keepaliveMs: 0, ...config });
  const connecting = c.connect(1000);
  await new Promise((resolve) => setTimeout(resolve, 0));
  const socket = FakeSocket.last;
  assert.equal(socket.sent[0].kind.case, "hello");
  for (const data of first) socket.deliver(data);
  await connecting;
  return { c, socket };
}

describe("what the client refuses from a server", () => {
  test("the Hello it sends carries the view, spectate, seat and contacts", async () => {
    const { socket } = await fakeSession([], {
      spectate: true,
      seat: 3,
      contacts: { bodyIds: [4n, 9n] },
      view: { encoding: "exact", interestRadius: 12.5, window: 7, byteBudget: 300 },
    });
    const hello = socket.sent[0].kind.value;
    assert.equal(hello.protocolVersion, 4);
    assert.equal(hello.spectate, true);
    assert.equal(hello.seat, 3);
    assert.deepEqual(hello.contacts.bodyIds, [4n, 9n]);
    assert.equal(hello.view.encoding, wire.Encoding.EXACT);
    assert.deepEqual(hello.view.interest, { case: "interestRadius", value: 12.5 });
    assert.equal(hello.view.window, 7);
    assert.equal(hello.view.byteBudget, 300);
    assert.equal(hello.view.positionPrecision, undefined, "a field left out stays out");
  });

  test("a message that does not parse: ProtocolError", async () => {
    const { c } = await fakeSession([serverMessage(welcome)]);
    assert.equal(c.state, ConnectionState.Connected);
    const snapshot = new Uint8Array(serverMessage({ case: "snapshot", value: { tick: 11n, exact: { idGaps: [3n], x: [1], y: [2], vx: [0], vy: [0] } } }));
    FakeSocket.last.deliver(snapshot.slice(0, snapshot.length - 4).buffer);
    assert.equal(c.state, ConnectionState.ProtocolError);
    assert.match(c.lastError.detail, /does not parse/);
  });

  test("a Snapshot before Welcome, a second Welcome, a text message, a message over the limit", async () => {
    const cases = [
      [[serverMessage({ case: "snapshot", value: { tick: 1n } })], /before Welcome/, {}],
      [[serverMessage(welcome), serverMessage(welcome)], /second Welcome/, {}],
      [[serverMessage(welcome), "text"], /text/, {}],
      [[serverMessage(welcome), new ArrayBuffer(2000)], /over the limit/, { maxMessageBytes: 1024 }],
    ];
    for (const [messages, why, config] of cases) {
      const { c } = await fakeSession(messages, config);
      assert.equal(c.state, ConnectionState.ProtocolError, String(why));
      assert.match(c.lastError.detail, why);
    }
  });

  test("a snapshot that does not apply (its tick going back): ProtocolError", async () => {
    const { c, socket } = await fakeSession([serverMessage(welcome)]);
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 12n, full: true } }));
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 11n } }));
    assert.equal(c.state, ConnectionState.ProtocolError);
    assert.match(c.lastError.detail, /before the last/);
  });

  test("a view hash that differs: one FullStateRequest until a full state arrives", async () => {
    const { c, socket } = await fakeSession([serverMessage(welcome)]);
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 11n, full: true, viewHash: 1n } }));
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 12n, viewHash: 2n } }));
    const asked = socket.sent.filter((m) => m.kind.case === "fullStateRequest").length;
    assert.equal(asked, 1);
    assert.equal(c.stats.desyncs, 2);
    const first = await c.nextSnapshot(0);
    assert.equal(first.inSync, false);
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 13n, full: true, viewHash: 0xcbf29ce484222325n } }));
    await c.nextSnapshot(0);
    const last = await c.nextSnapshot(0);
    assert.equal(last.inSync, true);
    const acks = socket.sent.filter((m) => m.kind.case === "ack").map((m) => m.kind.value.tick);
    assert.deepEqual(acks, [11n, 12n, 13n], "each snapshot taken is acknowledged");
  });

  test("the input fields are kept: they come only when they change", async () => {
    const { c, socket } = await fakeSession([serverMessage(welcome)]);
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 11n, full: true, hasAppliedInput: true, lastAppliedInputTick: 11n } }));
    socket.deliver(serverMessage({ case: "snapshot", value: { tick: 12n } }));
    await c.nextSnapshot(0);
    const second = await c.nextSnapshot(0);
    assert.equal(second.hasAppliedInput, true);
    assert.equal(second.lastAppliedInputTick, 11);
  });
});
