// A WebSocketLike (src/socket.ts) over a plain TCP connection in node, with the
// varint length prefix of docs/PROTOCOL.md 1.1 in place of WebSocket frames, so that
// the same Client can talk to the server's TCP port: pass it as ClientConfig.WebSocket
// with url "tcp://HOST:PORT". Each message handed to onmessage is one frame's payload.
// Used by bench/ws-vs-tcp.mjs to compare the two ports with one client program.
import { connect } from "node:net";

const CONNECTING = 0;
const OPEN = 1;
const CLOSING = 2;
const CLOSED = 3;

/** The frames of a stream: feed it bytes, get the payloads of the whole frames. */
export class FrameReader {
  #held = Buffer.alloc(0);

  constructor(maxFrameBytes) {
    this.maxFrameBytes = maxFrameBytes;
  }

  /** The payloads completed by `chunk`; throws on a varint over 10 bytes or a frame
   * over maxFrameBytes (checked before its payload is held). */
  feed(chunk) {
    const buf = this.#held.length === 0 ? chunk : Buffer.concat([this.#held, chunk]);
    const frames = [];
    let at = 0;
    for (;;) {
      let length = 0;
      let shift = 0;
      let p = at;
      let complete = false;
      while (p < buf.length) {
        const byte = buf[p++];
        // Plain arithmetic, not bit operators: a length may pass 2^31 before the check.
        length += (byte & 0x7f) * 2 ** shift;
        shift += 7;
        if ((byte & 0x80) === 0) {
          complete = true;
          break;
        }
        if (shift >= 70) throw new Error("frame length varint over 10 bytes");
      }
      if (!complete) break;
      if (length > this.maxFrameBytes) throw new Error(`frame of ${length} bytes over ${this.maxFrameBytes}`);
      if (buf.length - p < length) break;
      frames.push(buf.subarray(p, p + length));
      at = p + length;
    }
    // Copied, so that the held remainder does not pin the whole chunk.
    this.#held = Buffer.from(buf.subarray(at));
    return frames;
  }
}

/** The varint of `n` followed by `payload`, as one buffer (one write, one segment). */
export function frame(payload) {
  const prefix = [];
  let n = payload.length;
  while (n >= 0x80) {
    prefix.push((n % 0x80) | 0x80);
    n = Math.floor(n / 0x80);
  }
  prefix.push(n);
  const out = Buffer.allocUnsafe(prefix.length + payload.length);
  out.set(prefix, 0);
  out.set(payload, prefix.length);
  return out;
}

export class TcpSocket {
  binaryType = "arraybuffer";
  readyState = CONNECTING;
  onopen = null;
  onmessage = null;
  onclose = null;
  onerror = null;
  #socket;
  #reader;
  #closedByUs = false;

  /** url: tcp://HOST:PORT (an IPv6 host in brackets). */
  constructor(url, { maxFrameBytes = 1 << 24 } = {}) {
    const parsed = new URL(url);
    if (parsed.protocol !== "tcp:") throw new Error(`not a tcp:// url: ${url}`);
    this.#reader = new FrameReader(maxFrameBytes);
    this.#socket = connect({ host: parsed.hostname.replace(/^\[|\]$/g, ""), port: Number(parsed.port) });
    this.#socket.setNoDelay(true);
    this.#socket.on("connect", () => {
      this.readyState = OPEN;
      this.onopen?.({});
    });
    this.#socket.on("data", (chunk) => {
      let frames;
      try {
        frames = this.#reader.feed(chunk);
      } catch (error) {
        this.onerror?.(error);
        this.#socket.destroy();
        return;
      }
      for (const payload of frames) {
        // The client may close the socket while handling a message.
        if (this.readyState !== OPEN) return;
        this.onmessage?.({ data: payload });
      }
    });
    this.#socket.on("error", (error) => this.onerror?.(error));
    this.#socket.on("close", () => {
      this.readyState = CLOSED;
      // 1000 and 1006 as a WebSocket would report a clean and an abrupt end.
      this.onclose?.({ code: this.#closedByUs ? 1000 : 1006, reason: "" });
    });
  }

  /** Bytes read from and written to the connection, framing included (as node's
   * net.Socket counts them, and as the `ws` package's socket does under `_socket`). */
  get bytesRead() {
    return this.#socket.bytesRead;
  }
  get bytesWritten() {
    return this.#socket.bytesWritten;
  }

  send(data) {
    if (this.readyState !== OPEN) throw new Error("socket not open");
    this.#socket.write(frame(data));
  }

  close() {
    if (this.readyState === CLOSED || this.readyState === CLOSING) return;
    this.readyState = CLOSING;
    this.#closedByUs = true;
    this.#socket.end();
  }
}
