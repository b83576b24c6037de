// A client of physics-server over WebSocket (docs/PROTOCOL.md 1.3): connect (Hello,
// Welcome), send inputs, take snapshots. The shape of the C++ thin client
// (client/include/client/client.h), with promises where that one blocks: every call
// that waits takes a timeout and resolves to undefined when it runs out or the
// session ends (state tells which).
import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import * as wire from "./gen/wire_pb.js";
import { contactFromWire, contactsToWire, errorFromWire, shapeFromWire, viewToWire, welcomeFromWire } from "./convert.js";
import { Predictor } from "./predictor.js";
import { Quantum, Reconstruction } from "./reconstruction.js";
import { SOCKET_OPEN, WebSocketConstructor, WebSocketLike, globalWebSocket, messageBytes } from "./socket.js";
import {
  BodyShape,
  BodyState,
  ClientError,
  ClientStats,
  ConnectionState,
  ContactSubscription,
  GameMessage,
  PROTOCOL_VERSION,
  Pong,
  ServerError,
  Snapshot,
  ViewRequest,
  Welcome,
  findBody,
  isFailure,
} from "./types.js";

export interface ClientConfig {
  /** ws://HOST:PORT/ of the server's --ws-port. */
  url: string;
  /** The WebSocket to use; default: the global one (browsers, node 22+). In node 20,
   * pass the `ws` package's. */
  WebSocket?: WebSocketConstructor;
  name?: string;
  /** Hello.access_token; none sent when empty. */
  token?: string;
  /** Sent in Hello; only tests of the version refusal change it. */
  protocolVersion?: number;
  /** Messages from the server larger than this end the session (ProtocolError).
   * Default 1 MiB. */
  maxMessageBytes?: number;
  /** Snapshots received and not yet taken are kept up to this count; older ones are
   * dropped (and counted). Default 4096. */
  maxBufferedSnapshots?: number;
  /** When nothing has been sent for this long (ms), a Ping goes, so that a client
   * that only watches is not dropped as idle. 0 turns it off. Default 2000. */
  keepaliveMs?: number;
  view?: ViewRequest;
  spectate?: boolean;
  seat?: number;
  contacts?: ContactSubscription;
  /** The clock snapshots and pongs are stamped with (ms). Default performance.now. */
  now?: () => number;
}

/** Buffered errors, pongs and game messages are few in a healthy session; the bound
 * only stops a misbehaving server from growing them without limit. */
const MAX_SMALL_EVENTS = 256;

function emptyStats(): ClientStats {
  return {
    bytesReceived: 0,
    bytesSent: 0,
    snapshotsReceived: 0,
    snapshotsDropped: 0,
    errorsReceived: 0,
    inputsSent: 0,
    recordsReceived: 0,
    acksSent: 0,
    desyncs: 0,
    viewHashesChecked: 0,
    fullStatesReceived: 0,
  };
}

interface Waiter {
  ready: () => boolean;
  wake: () => void;
}

export class Client {
  private readonly config: Required<Omit<ClientConfig, "WebSocket" | "view" | "seat" | "contacts">> &
    Pick<ClientConfig, "view" | "seat" | "contacts">;
  private readonly WebSocketImpl: WebSocketConstructor;
  private socket: WebSocketLike | undefined;
  private state_ = ConnectionState.Disconnected;
  private error_: ClientError = { state: ConnectionState.Disconnected, detail: "" };
  private stats_ = emptyStats();
  private welcome_: Welcome | undefined;
  private nextSequence = 1n;
  private lastSent = 0;
  private keepaliveTimer: ReturnType<typeof setInterval> | undefined;
  private snapshots: Snapshot[] = [];
  private errors: ServerError[] = [];
  private pongs: Pong[] = [];
  private gameMessages: GameMessage[] = [];
  private waiters = new Set<Waiter>();
  private reconstruction = new Reconstruction();
  /** The kinematic bodies among those sent (Welcome, Snapshot.added): each snapshot's
   * BodyState.motion comes from it. */
  private kinematicIds = new Set<bigint>();
  private predictor: Predictor | undefined;
  private quantum: Quantum = { position: 0.001, velocity: 0.001 };
  private hasAppliedInput = false;
  private lastAppliedInputTick = 0;
  private inSync = true;
  private fullStateAsked = false;
  private close_: { code: number; reason: string } | undefined;

  constructor(config: ClientConfig) {
    const Impl = config.WebSocket ?? globalWebSocket();
    if (!Impl) throw new Error("no WebSocket: pass ClientConfig.WebSocket (in node 20, the `ws` package's)");
    this.WebSocketImpl = Impl;
    this.config = {
      url: config.url,
      name: config.name ?? "physics-client-web",
      token: config.token ?? "",
      protocolVersion: config.protocolVersion ?? PROTOCOL_VERSION,
      maxMessageBytes: config.maxMessageBytes ?? 1 << 20,
      maxBufferedSnapshots: config.maxBufferedSnapshots ?? 4096,
      keepaliveMs: config.keepaliveMs ?? 2000,
      now: config.now ?? (() => performance.now()),
      view: config.view,
      spectate: config.spectate ?? false,
      seat: config.seat,
      contacts: config.contacts,
    };
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
    return this.snapshots.length;
  }
  /** The clock (ms) snapshots and pongs are stamped with, and pings carry. */
  now(): number {
    return this.config.now();
  }
  /** The view hash (docs/PROTOCOL.md 5.6) of what this client holds now. */
  viewHash(): bigint {
    return this.reconstruction.hash();
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
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        this.waiters.delete(waiter);
        if (this.state_ === ConnectionState.Connecting) {
          this.fail(ConnectionState.ConnectTimedOut, `no connection within ${timeoutMs} ms`);
        } else if (this.state_ === ConnectionState.AwaitingWelcome) {
          this.fail(ConnectionState.WelcomeTimedOut, `no Welcome within ${timeoutMs} ms`);
        }
        resolve(this.state_ === ConnectionState.Connected);
      }, timeoutMs);
      const waiter: Waiter = {
        ready: () => this.state_ === ConnectionState.Connected || isFailure(this.state_) || this.state_ === ConnectionState.Disconnected,
        wake: () => {
          clearTimeout(timer);
          resolve(this.state_ === ConnectionState.Connected);
        },
      };
      this.waiters.add(waiter);
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
    if (sent) this.fullStateAsked = true;
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
    if (!(await this.waitUntil(() => this.snapshots.length > 0, timeoutMs))) return undefined;
    const snapshot = this.snapshots.shift()!;
    this.taken(snapshot);
    return snapshot;
  }

  /** The newest snapshot received, dropping older ones not yet taken; waits only
   * when none is buffered. */
  async newestSnapshot(timeoutMs: number): Promise<Snapshot | undefined> {
    if (!(await this.waitUntil(() => this.snapshots.length > 0, timeoutMs))) return undefined;
    const snapshot = this.snapshots[this.snapshots.length - 1];
    this.snapshots = [];
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
    await this.waitUntil(() => this.errors.length > 0, timeoutMs);
    return this.errors.shift();
  }

  async nextPong(timeoutMs: number): Promise<Pong | undefined> {
    await this.waitUntil(() => this.pongs.length > 0, timeoutMs);
    return this.pongs.shift();
  }

  /** The pongs received and not yet taken, oldest first (at most 256 are kept). */
  takePongs(): Pong[] {
    const pongs = this.pongs;
    this.pongs = [];
    return pongs;
  }

  /** The game's messages received so far, oldest first (at most 256 are kept). */
  takeGameMessages(): GameMessage[] {
    const messages = this.gameMessages;
    this.gameMessages = [];
    return messages;
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
    this.snapshots = [];
    this.errors = [];
    this.pongs = [];
    this.gameMessages = [];
    this.reconstruction = new Reconstruction();
    this.kinematicIds = new Set<bigint>();
    this.predictor = undefined;
    this.hasAppliedInput = false;
    this.lastAppliedInputTick = 0;
    this.inSync = true;
    this.fullStateAsked = false;
    this.nextSequence = 1n;
    this.close_ = undefined;
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
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        this.waiters.delete(waiter);
        resolve(ready());
      }, timeoutMs);
      const waiter: Waiter = {
        ready: () => ready() || this.state_ !== ConnectionState.Connected,
        wake: () => {
          clearTimeout(timer);
          resolve(ready());
        },
      };
      this.waiters.add(waiter);
    });
  }

  private notify(): void {
    for (const waiter of [...this.waiters]) {
      if (waiter.ready()) {
        this.waiters.delete(waiter);
        waiter.wake();
      }
    }
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
    const bytes = messageBytes(data);
    if (!bytes) {
      this.fail(ConnectionState.ProtocolError, "the server sent a text message");
      return;
    }
    this.stats_.bytesReceived += bytes.length;
    if (bytes.length > this.config.maxMessageBytes) {
      this.fail(
        ConnectionState.ProtocolError,
        `server message of ${bytes.length} bytes is over the limit of ${this.config.maxMessageBytes}`,
      );
      return;
    }
    let message: wire.ServerMessage;
    try {
      message = fromBinary(wire.ServerMessageSchema, bytes);
    } catch {
      this.fail(ConnectionState.ProtocolError, "server sent a message that does not parse");
      return;
    }
    const kind = message.kind;
    switch (kind.case) {
      case "welcome": {
        if (this.state_ !== ConnectionState.AwaitingWelcome) {
          this.fail(ConnectionState.ProtocolError, "server sent a second Welcome");
          return;
        }
        const welcome = welcomeFromWire(kind.value);
        if (!(welcome.tickRate > 0) || !Number.isFinite(welcome.tickRate)) {
          this.fail(ConnectionState.ProtocolError, `server sent a tick rate of ${welcome.tickRate}`);
          return;
        }
        this.welcome_ = welcome;
        this.noteKinematic(welcome.bodies, []);
        this.predictor = new Predictor(welcome.tickRate, welcome.gravity.x, welcome.gravity.y);
        this.quantum = { position: welcome.view.positionPrecision, velocity: welcome.view.velocityPrecision };
        this.state_ = ConnectionState.Connected;
        this.startKeepalive();
        break;
      }
      case "snapshot":
        if (this.state_ !== ConnectionState.Connected) {
          this.fail(ConnectionState.ProtocolError, "server sent a Snapshot before Welcome");
          return;
        }
        this.onSnapshot(kind.value, bytes.length);
        break;
      case "error": {
        const error = errorFromWire(kind.value);
        this.stats_.errorsReceived += 1;
        if (this.errors.length >= MAX_SMALL_EVENTS) this.errors.shift();
        this.errors.push(error);
        if (error.fatal) {
          this.error_ = { ...this.error_, server: error };
          this.fail(
            this.state_ === ConnectionState.AwaitingWelcome ? ConnectionState.Refused : ConnectionState.ConnectionLost,
            `${error.code}: ${error.message}`,
          );
          return;
        }
        break;
      }
      case "pong":
        if (this.pongs.length >= MAX_SMALL_EVENTS) this.pongs.shift();
        this.pongs.push({
          nonce: kind.value.nonce,
          clientTimeNs: kind.value.clientTimeNs,
          serverTick: Number(kind.value.serverTick),
          receivedAt: this.config.now(),
        });
        break;
      case "gameMessage":
        if (this.gameMessages.length >= MAX_SMALL_EVENTS) this.gameMessages.shift();
        this.gameMessages.push({ tick: Number(kind.value.tick), payload: kind.value.payload });
        break;
      default:
        // A kind newer than this client: ignored, as proto3 intends.
        return;
    }
    this.notify();
  }

  private noteKinematic(added: BodyShape[], removed: bigint[]): void {
    for (const id of removed) this.kinematicIds.delete(id);
    for (const shape of added) if (shape.motion === "kinematic") this.kinematicIds.add(shape.bodyId);
  }

  private onSnapshot(message: wire.Snapshot, wireBytes: number): void {
    // The input fields come only when they change.
    if (message.hasAppliedInput) this.hasAppliedInput = true;
    if (message.lastAppliedInputTick !== 0n) this.lastAppliedInputTick = Number(message.lastAppliedInputTick);
    const problem = this.reconstruction.apply(message, this.predictor!, this.quantum);
    if (problem) {
      this.fail(ConnectionState.ProtocolError, `server sent a snapshot that does not apply: ${problem}`);
      return;
    }
    const records =
      (message.quantized?.idGaps.length ?? 0) +
      (message.velocities?.idGaps.length ?? 0) +
      (message.exact?.idGaps.length ?? 0) +
      message.bodies.length;
    const added = message.added.map(shapeFromWire);
    const removed = [...message.removed];
    this.noteKinematic(added, removed);
    const held = this.reconstruction.bodies();
    const bodies: BodyState[] = new Array(held.length);
    for (let i = 0; i < held.length; ++i) {
      const b = held[i];
      bodies[i] = {
        bodyId: b.id,
        position: { x: b.x, y: b.y },
        velocity: { x: b.vx, y: b.vy },
        motion: this.kinematicIds.has(b.id) ? "kinematic" : "dynamic",
      };
    }
    if (message.full) {
      this.fullStateAsked = false;
      this.stats_.fullStatesReceived += 1;
    }
    // The hash comes with every k-th snapshot (view_hash_interval); in between, the
    // last comparison holds.
    if (message.viewHash !== undefined) {
      this.stats_.viewHashesChecked += 1;
      this.inSync = this.reconstruction.hash() === message.viewHash;
      if (!this.inSync) {
        this.stats_.desyncs += 1;
        if (!this.fullStateAsked) this.requestFullState();
      }
    }
    const snapshot: Snapshot = {
      tick: Number(message.tick),
      stateHash: message.stateHash,
      bodies,
      own: undefined,
      hasAppliedInput: this.hasAppliedInput,
      lastAppliedInputTick: this.lastAppliedInputTick,
      added,
      removed,
      contactEvents: message.contactEvents.map(contactFromWire),
      contactEventsDropped: message.contactEventsDropped,
      inputMarginUs: message.inputMarginUs === undefined ? undefined : Number(message.inputMarginUs),
      bodiesMissing: message.bodiesMissing,
      records,
      full: message.full,
      viewHash: message.viewHash,
      inSync: this.inSync,
      receivedAt: this.config.now(),
      wireBytes,
    };
    if (this.welcome_ && !this.welcome_.spectator) snapshot.own = findBody(snapshot, this.welcome_.bodyId);
    this.stats_.snapshotsReceived += 1;
    this.stats_.recordsReceived += records;
    if (this.snapshots.length >= this.config.maxBufferedSnapshots) {
      this.snapshots.shift();
      this.stats_.snapshotsDropped += 1;
    }
    this.snapshots.push(snapshot);
  }
}
