// What the client hands out: plain objects converted from the wire messages
// (proto/wire.proto), so that callers never see Protobuf. Field meanings are those
// docs/PROTOCOL.md gives for the messages they come from. Body ids, hashes and
// other 64-bit fields are bigints; ticks are numbers (exact below 2^53).

/** The protocol version this client speaks (physics.wire.PROTOCOL_VERSION_CURRENT). */
export const PROTOCOL_VERSION = 4;

export interface Vec2 {
  x: number;
  y: number;
}

export type ShapeType = "unspecified" | "circle" | "box";

/** How a body moves: never (static), by forces and contacts (dynamic), or by its
 * velocity alone, pushing what it meets (kinematic). */
export type Motion = "static" | "dynamic" | "kinematic";

/** Which bodies a body collides with: two bodies of the same nonzero group always
 * (positive) or never (negative) collide; otherwise each one's mask must hold the
 * other's category. */
export interface CollisionFilter {
  categoryBits: number;
  maskBits: number;
  group: number;
}

/** A body's shape and material, sent once (in Welcome or Snapshot.added): with the
 * state the snapshots carry, every field the world's state hash covers
 * (docs/PROTOCOL.md 5.11). */
export interface BodyShape {
  bodyId: bigint;
  shape: ShapeType;
  radius: number;
  halfExtents: Vec2;
  isStatic: boolean;
  isKinematic: boolean;
  isSensor: boolean;
  /** Where it was when sent; static bodies stay there. */
  position: Vec2;
  mass: number;
  restitution: number;
  friction: Vec2;
  name: string;
  /** The same as isStatic and isKinematic say. */
  motion: Motion;
  /** When sent; a kinematic body keeps it until the rules change it. */
  velocity: Vec2;
  /** When sent (dynamic bodies only). */
  acceleration: Vec2;
  contactFriction: number;
  filter: CollisionFilter;
}

/** Half the size of the axis-aligned box a body occupies: a box's half extents, a
 * circle's (radius, radius). */
export function boxHalfSize(shape: BodyShape): Vec2 {
  return shape.shape === "box" ? shape.halfExtents : { x: shape.radius, y: shape.radius };
}

/** A moving (dynamic or kinematic) body's state after a tick. */
export interface BodyState {
  bodyId: bigint;
  position: Vec2;
  velocity: Vec2;
  /** Its shape's (Welcome or Snapshot.added): "dynamic" or "kinematic". */
  motion: Motion;
}

export type Encoding = "predicted" | "exact" | "full" | "inputs";

export interface Rect {
  minX: number;
  minY: number;
  maxX: number;
  maxY: number;
}

/** What a client asks for in Hello.view; a field left out takes the server's default
 * (docs/PROTOCOL.md 5.1). */
export interface ViewRequest {
  encoding?: Encoding;
  positionPrecision?: number;
  velocityPrecision?: number;
  positionTolerance?: number;
  velocityTolerance?: number;
  snapshotInterval?: number;
  window?: number;
  interestRadius?: number;
  interestRect?: Rect;
  byteBudget?: number;
  stateHash?: boolean;
  viewHashInterval?: number;
}

/** The view in force, as Welcome.view gives it. */
export interface View {
  encoding: Encoding;
  positionPrecision: number;
  velocityPrecision: number;
  positionTolerance: number;
  velocityTolerance: number;
  snapshotInterval: number;
  window: number;
  interestRadius?: number;
  interestRect?: Rect;
  byteBudget: number;
  stateHash: boolean;
  viewHashInterval: number;
}

export interface Welcome {
  protocolVersion: number;
  clientId: number;
  /** The body this client controls (0n for a spectator). */
  bodyId: bigint;
  tickRate: number;
  /** The last tick stepped when the client joined. */
  currentTick: number;
  bodies: BodyShape[];
  gravity: Vec2;
  maxAcceleration: number;
  lockstep: boolean;
  maxTicksAhead: number;
  sceneName: string;
  view: View;
  maxPlayers: number;
  spectator: boolean;
  seat: number;
  seats: number;
}

/** Which contact events to receive (Hello.contacts): a player leaves both empty (its
 * own body's), a spectator sets `all` or lists up to 64 body ids. */
export interface ContactSubscription {
  all?: boolean;
  bodyIds?: bigint[];
}

/** Two bodies began (or, with `end`, stopped) touching in tick `tick`. */
export interface ContactEvent {
  end: boolean;
  tick: number;
  bodyA: bigint;
  bodyB: bigint;
  point: Vec2;
  normal: Vec2;
  closingSpeed: number;
}

/** The world after tick `tick` as this client holds it: every moving (dynamic or
 * kinematic) body of its view, reconstructed from what the server sent. */
export interface Snapshot {
  tick: number;
  /** The world's state hash, when the view asked for it (else 0n). */
  stateHash: bigint;
  /** Every body held, ascending id. */
  bodies: BodyState[];
  /** The own body's state (a player's, when held). */
  own?: BodyState;
  hasAppliedInput: boolean;
  lastAppliedInputTick: number;
  added: BodyShape[];
  removed: bigint[];
  contactEvents: ContactEvent[];
  contactEventsDropped: number;
  inputMarginUs?: number;
  /** Under a byte budget: bodies of the view not held yet. */
  bodiesMissing: number;
  /** Body records this snapshot carried (the rest were predicted). */
  records: number;
  full: boolean;
  /** The server's view hash, when this snapshot carried one. */
  viewHash?: bigint;
  /** Whether our view hash equalled the server's at the last snapshot carrying one. */
  inSync: boolean;
  /** Local: when it was decoded (ms, performance.now()), and its bytes on the wire. */
  receivedAt: number;
  wireBytes: number;
}

/** The number of a body in a snapshot, by binary search over its ascending ids. */
export function findBody(snapshot: Snapshot, bodyId: bigint): BodyState | undefined {
  const bodies = snapshot.bodies;
  let lo = 0;
  let hi = bodies.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (bodies[mid].bodyId < bodyId) lo = mid + 1;
    else hi = mid;
  }
  return lo < bodies.length && bodies[lo].bodyId === bodyId ? bodies[lo] : undefined;
}

export interface GameMessage {
  tick: number;
  payload: Uint8Array;
}

export interface Pong {
  nonce: bigint;
  clientTimeNs: bigint;
  serverTick: number;
  receivedAt: number;
}

/** An Error message as the server sent it. `code` is physics.wire.ErrorCode's name
 * without its prefix ("PROTOCOL_VERSION"), or the number for codes newer than ours. */
export interface ServerError {
  code: string;
  rawCode: number;
  message: string;
  fatal: boolean;
}

/** The connection's states (docs/PROTOCOL.md 7): negative values are failures. */
export enum ConnectionState {
  ConnectionLost = -6,
  ProtocolError = -5,
  Refused = -4,
  WelcomeTimedOut = -3,
  ConnectTimedOut = -2,
  ConnectFailed = -1,
  Disconnected = 0,
  Connecting = 1,
  AwaitingWelcome = 2,
  Connected = 3,
}

export function isFailure(state: ConnectionState): boolean {
  return state < 0;
}

/** Why the client is not (or no longer) connected. */
export interface ClientError {
  state: ConnectionState;
  /** Set when the server said why (an Error message). */
  server?: ServerError;
  /** Our own description: the close, the timeout, what did not parse. */
  detail: string;
}

export interface ClientStats {
  bytesReceived: number;
  bytesSent: number;
  snapshotsReceived: number;
  snapshotsDropped: number;
  errorsReceived: number;
  inputsSent: number;
  recordsReceived: number;
  acksSent: number;
  /** Snapshots whose view hash differed from ours. */
  desyncs: number;
  /** Snapshots whose view hash was compared (and equal or not). */
  viewHashesChecked: number;
  fullStatesReceived: number;
}
