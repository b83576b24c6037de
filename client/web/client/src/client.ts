// A client of physics-server over WebSocket (docs/PROTOCOL.md 1.3): connect (Hello,
// Welcome), send inputs, take snapshots. The shape of the C++ thin client
// (client/include/client/client.h), with promises where that one blocks: every call
// that waits takes a timeout and resolves to undefined when it runs out or the
// session ends (state tells which).
import { create, toBinary } from "@bufbuild/protobuf";
import * as wire from "./gen/wire_pb.js";
import { ClientConfig, ResolvedConfig, resolveConfig } from "./client_config.js";
import { contactsToWire, viewToWire } from "./convert.js";
import { DispatchTarget, dispatch } from "./dispatch.js";
import { SessionInbox, emptyStats } from "./session_inbox.js";
import { SnapshotReader } from "./snapshot_reader.js";
import { SOCKET_OPEN, WebSocketConstructor, WebSocketLike, globalWebSocket } from "./socket.js";
import {
  ClientError,
  ClientStats,
  ConnectionState,
  GameMessage,
  Pong,
  ServerError,
  Snapshot,
  Welcome,
  isFailure,
} from "./types.js";
import { Waiters } from "./waiters.js";

export type { ClientConfig } from "./client_config.js";

export class Client {
  private readonly config: ResolvedConfig;
  private readonly WebSocketImpl: WebSocketConstructor;
  private socket: WebSocketLike | undefined;
  private state_ = ConnectionState.Disconnected;
  private error_: ClientError = { state: ConnectionState.Disconnected, detail: "" };
  private stats_ = emptyStats();
  private welcome_: Welcome | undefined;
  private nextSequence = 1n;
  private lastSent = 0;
  private keepaliveTimer: ReturnType<typeof setInterval> | undefined;
  private inbox: SessionInbox;
  private readonly waiters = new Waiters();
  private reader: SnapshotReader;
  private close_: { code: number; reason: string } | undefined;
  // This session's fields as dispatch.ts sees them: it handles the server's messages
  // and updates these.
  private readonly dispatchTarget: DispatchTarget = (() => {
    const client = this;
    return {
      get state() {
        return client.state_;
      },
      get stats() {
        return client.stats_;
      },
      get inbox() {
        return client.inbox;
      },
      get reader() {
        return client.reader;
      },
      get maxMessageBytes() {
        return client.config.maxMessageBytes;
      },
      now: () => client.config.now(),
      fail: (state: ConnectionState, detail: string) => client.fail(state, detail),
      welcomed: (welcome: Welcome) => {
        client.welcome_ = welcome;
        client.reader.start(welcome);
        client.state_ = ConnectionState.Connected;
        client.startKeepalive();
      },
      fatalError: (error: ServerError) => {
        client.error_ = { ...client.error_, server: error };
      },
      notify: () => client.notify(),
    };
  })();

  constructor(config: ClientConfig) {
    const Impl = config.WebSocket ?? globalWebSocket();
    if (!Impl) throw new Error("no WebSocket: pass ClientConfig.WebSocket (in node 20, the `ws` package's)");
    this.WebSocketImpl = Impl;
    this.config = resolveConfig(config);
    this.inbox = new SessionInbox(this.stats_, this.config.maxBufferedSnapshots);
    this.reader = this.newReader();
  }

  get state(): ConnectionState {
    return this.state_;
  }
  get lastError(): ClientError {
    return this.error_;
  }
  get stats(): ClientStats {
    return this.stats_;
  }
  /** The Welcome of the current session (set once connect() resolved true). */
  get welcome(): Welcome | undefined {
    return this.welcome_;
  }
  /** The close frame's code and reason, when the server closed the connection before
   * the client did (after a fatal Error the client closes at once, as the C++ one does). */
  get closeEvent(): { code: number; reason: string } | undefined {
    return this.close_;
  }
  get bufferedSnapshots(): number {
    return this.inbox.snapshots.length;
  }
  /** The clock (ms) snapshots and pongs are stamped with, and pings carry. */
  now(): number {
    return this.config.now();
  }
  /** The view hash (docs/PROTOCOL.md 5.6) of what this client holds now. */
  viewHash(): bigint {
    return this.reader.viewHash();
  }

  /**
   * Opens the WebSocket, sends Hello and waits for Welcome, all within `timeoutMs`.
   * True when Connected; otherwise state is a failure and lastError says why.
   */
  connect(timeoutMs = 5000): Promise<boolean> {
    this.closeSocket();
    this.resetSession();
    this.state_ = ConnectionState.Connecting;
    let socket: WebSocketLike;
    try {
      socket = new this.WebSocketImpl(this.config.url);
    } catch (error) {
      this.fail(ConnectionState.ConnectFailed, `cannot open ${this.config.url}: ${String(error)}`);
      return Promise.resolve(false);
    }
    this.socket = socket;
    socket.binaryType = "arraybuffer";
    socket.onopen = () => {
      if (this.socket !== socket) return;
      this.state_ = ConnectionState.AwaitingWelcome;
      this.sendHello();
      this.notify();
    };
    socket.onmessage = (event) => {
      if (this.socket === socket) this.onMessage(event.data);
    };
    socket.onerror = () => {
      if (this.socket !== socket) return;
      if (this.state_ === ConnectionState.Connecting) {
        this.fail(ConnectionState.ConnectFailed, `cannot connect to ${this.config.url}`);
      }
    };
    socket.onclose = (event) => {
      if (this.socket !== socket) return;
      this.close_ = { code: event.code, reason: event.reason };
      this.onClose(event.code);
    };
    const settled = () =>
      this.state_ === ConnectionState.Connected || isFailure(this.state_) || this.state_ === ConnectionState.Disconnected;
    return this.waiters.wait(settled, timeoutMs, (timedOut) => {
      if (timedOut && this.state_ === ConnectionState.Connecting) {
        this.fail(ConnectionState.ConnectTimedOut, `no connection within ${timeoutMs} ms`);
      } else if (timedOut && this.state_ === ConnectionState.AwaitingWelcome) {
        this.fail(ConnectionState.WelcomeTimedOut, `no Welcome within ${timeoutMs} ms`);
      }
      return this.state_ === ConnectionState.Connected;
    });
  }

  /** Sends Input{tick, ax, ay, sequence}; the sequence counts up from 1. */
  sendInput(tick: number, ax: number, ay: number): boolean {
    const sent = this.send({
      case: "input",
      value: create(wire.InputSchema, { tick: BigInt(tick), ax, ay, sequence: this.nextSequence }),
    });
    if (sent) {
      this.nextSequence += 1n;
      this.stats_.inputsSent += 1;
    }
    return sent;
  }

  sendPing(nonce: bigint | number, clientTimeNs?: bigint): boolean {
    const time = clientTimeNs ?? BigInt(Math.round(this.config.now() * 1e6));
    return this.send({ case: "ping", value: create(wire.PingSchema, { nonce: BigInt(nonce), clientTimeNs: time }) });
  }

  /** A message for the game's rules at `tick` (docs/PROTOCOL.md 3.9). */
  sendGameMessage(tick: number, payload: Uint8Array): boolean {
    return this.send({ case: "gameMessage", value: create(wire.GameMessageSchema, { tick: BigInt(tick), payload }) });
  }

  /** Asks the server for a full state (the client does so itself when its view hash
   * differs from the server's). */
  requestFullState(): boolean {
    const sent = this.send({ case: "fullStateRequest", value: create(wire.FullStateRequestSchema, {}) });
    if (sent) this.reader.fullStateAsked = true;
    return sent;
  }

  /** Bytes as one binary message, unchecked: for tests of the server's refusals. */
  sendRaw(bytes: Uint8Array): boolean {
    if (!this.socket || this.socket.readyState !== SOCKET_OPEN) return false;
    this.socket.send(bytes);
    this.stats_.bytesSent += bytes.length;
    this.lastSent = this.config.now();
    return true;
  }

  /** The oldest snapshot not yet taken, waiting up to `timeoutMs` for one. Taking a
   * snapshot acknowledges it: the server sends no more than the view's window of
   * snapshots not yet taken. */
  async nextSnapshot(timeoutMs: number): Promise<Snapshot | undefined> {
    if (!(await this.waitUntil(() => this.inbox.snapshots.length > 0, timeoutMs))) return undefined;
    const snapshot = this.inbox.snapshots.shift()!;
    this.taken(snapshot);
    return snapshot;
  }

  /** The newest snapshot received, dropping older ones not yet taken; waits only
   * when none is buffered. */
  async newestSnapshot(timeoutMs: number): Promise<Snapshot | undefined> {
    if (!(await this.waitUntil(() => this.inbox.snapshots.length > 0, timeoutMs))) return undefined;
    const snapshots = this.inbox.snapshots;
    const snapshot = snapshots[snapshots.length - 1];
    this.inbox.snapshots = [];
    this.taken(snapshot);
    return snapshot;
  }

  /** Waits for a snapshot satisfying `done`, taking (and dropping) those before it. */
  async waitForSnapshot(timeoutMs: number, done: (s: Snapshot) => boolean): Promise<Snapshot | undefined> {
    const deadline = this.config.now() + timeoutMs;
    for (;;) {
      const snapshot = await this.nextSnapshot(Math.max(0, deadline - this.config.now()));
      if (!snapshot) return undefined;
      if (done(snapshot)) return snapshot;
    }
  }

  /** The next Error from the server (non-fatal ones keep the session; a fatal one also
   * ends it). Snapshots arriving meanwhile stay buffered. */
  async nextError(timeoutMs: number): Promise<ServerError | undefined> {
    await this.waitUntil(() => this.inbox.errors.length > 0, timeoutMs);
    return this.inbox.errors.shift();
  }

  async nextPong(timeoutMs: number): Promise<Pong | undefined> {
    await this.waitUntil(() => this.inbox.pongs.length > 0, timeoutMs);
    return this.inbox.pongs.shift();
  }

  /** The pongs received and not yet taken, oldest first (at most 256 are kept). */
  takePongs(): Pong[] {
    return this.inbox.takePongs();
  }

  /** The game's messages received so far, oldest first (at most 256 are kept). */
  takeGameMessages(): GameMessage[] {
    return this.inbox.takeGameMessages();
  }

  /** Sends Bye and closes. The state becomes Disconnected. */
  disconnect(reason = "bye"): void {
    if (this.state_ === ConnectionState.Connected || this.state_ === ConnectionState.AwaitingWelcome) {
      this.send({ case: "bye", value: create(wire.ByeSchema, { reason }) });
    }
    this.closeSocket();
    this.state_ = ConnectionState.Disconnected;
    this.notify();
  }

  // ---- inside ----

  private resetSession(): void {
    this.error_ = { state: ConnectionState.Disconnected, detail: "" };
    this.welcome_ = undefined;
    this.inbox = new SessionInbox(this.stats_, this.config.maxBufferedSnapshots);
    this.reader = this.newReader();
    this.nextSequence = 1n;
    this.close_ = undefined;
  }

  private newReader(): SnapshotReader {
    return new SnapshotReader(
      this.stats_,
      () => this.config.now(),
      () => this.requestFullState(),
    );
  }

  private sendHello(): void {
    const hello = create(wire.HelloSchema, {
      protocolVersion: this.config.protocolVersion,
      clientName: this.config.name,
      accessToken: this.config.token,
      spectate: this.config.spectate,
      seat: this.config.seat,
    });
    if (this.config.view) hello.view = viewToWire(this.config.view);
    if (this.config.contacts) hello.contacts = contactsToWire(this.config.contacts);
    this.send({ case: "hello", value: hello });
  }

  private send(kind: wire.ClientMessage["kind"]): boolean {
    if (!this.socket || this.socket.readyState !== SOCKET_OPEN) return false;
    if (this.state_ !== ConnectionState.Connected && kind.case !== "hello" && kind.case !== "bye" && kind.case !== "ping") {
      return false;
    }
    const bytes = toBinary(wire.ClientMessageSchema, create(wire.ClientMessageSchema, { kind }));
    try {
      this.socket.send(bytes);
    } catch (error) {
      this.fail(ConnectionState.ConnectionLost, `send failed: ${String(error)}`);
      return false;
    }
    this.stats_.bytesSent += bytes.length;
    this.lastSent = this.config.now();
    return true;
  }

  private taken(snapshot: Snapshot): void {
    if (this.send({ case: "ack", value: create(wire.AckSchema, { tick: BigInt(snapshot.tick) }) })) {
      this.stats_.acksSent += 1;
    }
  }

  private waitUntil(ready: () => boolean, timeoutMs: number): Promise<boolean> {
    if (ready()) return Promise.resolve(true);
    if (this.state_ !== ConnectionState.Connected) return Promise.resolve(false);
    return this.waiters.wait(() => ready() || this.state_ !== ConnectionState.Connected, timeoutMs, () => ready());
  }

  private notify(): void {
    this.waiters.notify();
  }

  private fail(state: ConnectionState, detail: string): void {
    this.state_ = state;
    this.error_ = { ...this.error_, state, detail };
    this.closeSocket();
    this.notify();
  }

  private closeSocket(): void {
    if (this.keepaliveTimer !== undefined) {
      clearInterval(this.keepaliveTimer);
      this.keepaliveTimer = undefined;
    }
    const socket = this.socket;
    this.socket = undefined;
    if (!socket) return;
    socket.onopen = null;
    socket.onmessage = null;
    socket.onerror = null;
    socket.onclose = null;
    try {
      socket.close();
    } catch {
      // Closing a socket that never opened: nothing to do.
    }
  }

  private onClose(code: number): void {
    switch (this.state_) {
      case ConnectionState.Connecting:
        this.fail(ConnectionState.ConnectFailed, `cannot connect to ${this.config.url} (close ${code})`);
        return;
      case ConnectionState.AwaitingWelcome:
        this.fail(ConnectionState.ConnectionLost, `the server closed the connection before Welcome (close ${code})`);
        return;
      case ConnectionState.Connected:
        this.fail(ConnectionState.ConnectionLost, `the server closed the connection (close ${code})`);
        return;
      default:
        return;
    }
  }

  private startKeepalive(): void {
    const period = this.config.keepaliveMs;
    if (period <= 0) return;
    let nonce = 1n;
    this.keepaliveTimer = setInterval(() => {
      if (this.config.now() - this.lastSent >= period) this.sendPing(nonce++);
    }, Math.max(10, period / 4));
  }

  private onMessage(data: unknown): void {
    dispatch(this.dispatchTarget, data);
  }
}
