// A client that does on the wire what Client does, and no more: Hello, then for every
// snapshot an Ack and an Input (from onSnapshot). A snapshot is read only as far as
// its tick and applied to nothing (no bodies held, no view hash); Ack and Input are
// written by hand, the same bytes as toBinary's (test/bench.test.mjs checks both).
// The server cannot tell it from a Client whose view hash agrees, and it costs tens
// of microseconds a snapshot instead of hundreds, so that one node process can play
// 64 of them at 60 ticks a second (bench/ws-vs-tcp.mjs). Over any WebSocketLike
// (src/socket.ts): the `ws` package's, or bench/tcp-socket.mjs.
import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import { PROTOCOL_VERSION, wire } from "../dist/index.js";

/** Appends the base-128 varint of n (an integer below 2^53) to out. */
function pushVarint(out, n) {
  while (n >= 0x80) {
    out.push((n % 0x80) | 0x80);
    n = Math.floor(n / 0x80);
  }
  out.push(n);
}

function pushDouble(out, field, x) {
  // proto3 leaves out a field equal to its default; -0 too, as toBinary does.
  if (x === 0) return;
  out.push((field << 3) | 1, ...new Uint8Array(new Float64Array([x]).buffer));
}

function envelope(field, body) {
  const out = [(field << 3) | 2];
  pushVarint(out, body.length);
  return Uint8Array.from([...out, ...body]);
}

/** ClientMessage{ack{tick}}. */
export function encodeAck(tick) {
  const body = [];
  if (tick !== 0) {
    body.push(0x08);
    pushVarint(body, tick);
  }
  return envelope(5, body);
}

/** ClientMessage{input{tick, ax, ay, sequence}}. */
export function encodeInput(tick, ax, ay, sequence) {
  const body = [];
  if (tick !== 0) {
    body.push(0x08);
    pushVarint(body, tick);
  }
  pushDouble(body, 2, ax);
  pushDouble(body, 3, ay);
  if (sequence !== 0) {
    body.push(0x20);
    pushVarint(body, sequence);
  }
  return envelope(2, body);
}

/** The tick of a ServerMessage{snapshot}, undefined for any other message. The
 * server writes the snapshot's fields in field order, so a tick comes first (and is
 * absent when 0). */
export function snapshotTick(bytes) {
  if (bytes[0] !== 0x12) return undefined;
  let at = 1;
  while (bytes[at] & 0x80) ++at;  // the snapshot's length
  ++at;
  if (bytes[at] !== 0x08) return 0;
  let tick = 0;
  for (let scale = 1; ; scale *= 0x80) {
    const byte = bytes[++at];
    tick += (byte & 0x7f) * scale;
    if (!(byte & 0x80)) return tick;
  }
}

export class LightClient {
  stats = { bytesSent: 0, bytesReceived: 0, snapshotsReceived: 0, inputsSent: 0, acksSent: 0 };
  connected = false;
  detail = "";
  #socket;
  #sequence = 1;
  #onConnect = () => {};

  /** onSnapshot(client, tick): called for each snapshot, after its Ack is sent. */
  constructor({ url, WebSocket, name, onSnapshot }) {
    this.url = url;
    this.WebSocket = WebSocket;
    this.name = name;
    this.onSnapshot = onSnapshot;
  }

  /** Resolves true once Welcome came within timeoutMs; otherwise false, and detail
   * says why (a fatal Error as "CODE: message", as Client's lastError.detail). */
  connect(timeoutMs) {
    this.connected = false;
    this.detail = "";
    const socket = new this.WebSocket(this.url);
    this.#socket = socket;
    socket.binaryType = "arraybuffer";
    socket.onopen = () =>
      this.#send({
        case: "hello",
        value: create(wire.HelloSchema, { protocolVersion: PROTOCOL_VERSION, clientName: this.name }),
      });
    socket.onmessage = (event) => this.#onMessage(event.data);
    socket.onerror = () => {};
    socket.onclose = () => this.#end(this.detail || "the server closed the connection");
    return new Promise((resolve) => {
      const timer = setTimeout(() => this.#end("no Welcome in time"), timeoutMs);
      this.#onConnect = (ok) => {
        clearTimeout(timer);
        this.#onConnect = () => {};
        resolve(ok);
      };
    });
  }

  sendInput(tick, ax, ay) {
    if (this.#sendBytes(encodeInput(tick, ax, ay, this.#sequence))) {
      this.#sequence += 1;
      this.stats.inputsSent += 1;
    }
  }

  disconnect() {
    if (this.connected) this.#send({ case: "bye", value: create(wire.ByeSchema, { reason: "bye" }) });
    this.connected = false;
    this.#close();
  }

  #send(kind) {
    return this.#sendBytes(toBinary(wire.ClientMessageSchema, create(wire.ClientMessageSchema, { kind })));
  }

  #sendBytes(bytes) {
    if (!this.#socket || this.#socket.readyState !== 1) return false;
    this.#socket.send(bytes);
    this.stats.bytesSent += bytes.length;
    return true;
  }

  #onMessage(data) {
    const bytes = data instanceof ArrayBuffer ? new Uint8Array(data) : data;
    this.stats.bytesReceived += bytes.length;
    const tick = snapshotTick(bytes);
    if (tick !== undefined) {
      this.stats.snapshotsReceived += 1;
      if (this.#sendBytes(encodeAck(tick))) this.stats.acksSent += 1;
      this.onSnapshot(this, tick);
      return;
    }
    const kind = fromBinary(wire.ServerMessageSchema, bytes).kind;
    if (kind.case === "welcome") {
      this.connected = true;
      this.#onConnect(true);
    } else if (kind.case === "error" && kind.value.fatal) {
      const code = (wire.ErrorCode[kind.value.code] ?? String(kind.value.code)).replace(/^ERROR_/, "");
      this.#end(`${code}: ${kind.value.message}`);
    }
  }

  #end(detail) {
    if (!this.detail) this.detail = detail;
    this.connected = false;
    this.#close();
    this.#onConnect(false);
  }

  #close() {
    const socket = this.#socket;
    this.#socket = undefined;
    if (!socket) return;
    socket.onopen = socket.onmessage = socket.onclose = null;
    socket.close();
  }
}
