// A playout buffer: snapshot interpolation (Fiedler, "Snapshot Interpolation"), the
// C++ client's (client/include/client/playout_buffer.h) in TypeScript, with the
// same settings, results and bounds.
//
// Snapshots go in as they arrive, each with its arrival time on the caller's clock
// (seconds, any origin). stateAt(now) returns every body at a server time a little in
// the past,
//
//   shown = estimated newest server time now - delay,
//   delay = sendIntervals * sendInterval + jitterMultiplier * jitter,
//           clamped to [minDelay, maxDelay],
//
// interpolating linearly between the two snapshots around it. The newest server time
// now is `now - offset`, offset the smallest (arrival - server time) among the
// snapshots held; jitter is RFC 3550's smoothed mean of |D|, D the change in transit
// time between consecutive snapshots (gain 1/16). The shown time is steered toward
// its target at most `slew` seconds per second; a target further than `snap` away is
// jumped to. Between two snapshots more than one send interval apart the earlier one
// is carried forward at its velocity until one interval before the later one, then
// interpolated. Past the newest snapshot each body is extrapolated at its velocity for
// at most maxExtrapolation seconds, then held.
import type { BodyState, Motion, Snapshot, Vec2 } from "./types.js";

export interface PlayoutSettings {
  /** The server's tick rate: a tick's server time is tick / rate. */
  tickRate: number;
  /** The time between two snapshots the server sends (s): the view's
   * snapshot_interval / tick_rate. 0: one tick. */
  sendInterval: number;
  sendIntervals: number;
  jitterMultiplier: number;
  minDelay: number;
  maxDelay: number;
  maxExtrapolation: number;
  slew: number;
  snap: number;
  maxGap: number;
  capacity: number;
}

export function defaultPlayoutSettings(): PlayoutSettings {
  return {
    tickRate: 60,
    sendInterval: 0,
    sendIntervals: 3,
    jitterMultiplier: 3,
    minDelay: 0,
    maxDelay: 1,
    maxExtrapolation: 0.25,
    slew: 0.1,
    snap: 1,
    maxGap: 5,
    capacity: 64,
  };
}

/** Empty when every field is in range; otherwise what is wrong, for a person. */
export function validatePlayoutSettings(s: PlayoutSettings): string {
  const within = (value: number, low: number, high: number) => Number.isFinite(value) && value >= low && value <= high;
  const bad = (field: string, value: number, range: string) => `${field} = ${value} is out of range ${range}`;
  if (!within(s.tickRate, 1e-3, 1e6)) return bad("tickRate", s.tickRate, "(0, 1e6]");
  if (!within(s.sendInterval, 0, 60)) return bad("sendInterval", s.sendInterval, "[0, 60]");
  if (!within(s.sendIntervals, 0, 100)) return bad("sendIntervals", s.sendIntervals, "[0, 100]");
  if (!within(s.jitterMultiplier, 0, 100)) return bad("jitterMultiplier", s.jitterMultiplier, "[0, 100]");
  if (!within(s.minDelay, 0, 60)) return bad("minDelay", s.minDelay, "[0, 60]");
  if (!within(s.maxDelay, s.minDelay, 60)) return bad("maxDelay", s.maxDelay, "[minDelay, 60]");
  if (!within(s.maxExtrapolation, 0, 60)) return bad("maxExtrapolation", s.maxExtrapolation, "[0, 60]");
  if (!within(s.slew, 0, 1)) return bad("slew", s.slew, "[0, 1]");
  if (!within(s.snap, 1e-6, 3600)) return bad("snap", s.snap, "(0, 3600]");
  if (!within(s.maxGap, 1e-6, 1e9)) return bad("maxGap", s.maxGap, "(0, 1e9]");
  if (!Number.isInteger(s.capacity) || s.capacity < 2 || s.capacity > 1 << 20) {
    return `capacity = ${s.capacity} is out of range [2, 1048576]`;
  }
  return "";
}

export type PushResult = "accepted" | "reset" | "stale" | "bad-time" | "bad-state";
export type PlayoutStatus = "empty" | "early" | "interpolating" | "extrapolating" | "holding";

export interface PlayoutBody {
  bodyId: bigint;
  position: Vec2;
  velocity: Vec2;
  /** Its state is the same, bit for bit, in the two newest snapshots held. */
  still: boolean;
  /** The snapshot's BodyState.motion: "dynamic" or "kinematic". */
  motion: Motion;
}

export interface PlayoutFrame {
  status: PlayoutStatus;
  /** s: the server time shown (tick / tickRate). */
  serverTime: number;
  /** s: estimated newest server time now minus serverTime. */
  lag: number;
  /** s past the newest snapshot (extrapolating, holding). */
  extrapolated: number;
  newestTick: number;
  /** Every body of the snapshots around, ascending id. */
  bodies: PlayoutBody[];
}

export interface PlayoutStats {
  accepted: number;
  stale: number;
  badTime: number;
  badState: number;
  resets: number;
  clockBackwards: number;
  snaps: number;
  dropped: number;
}

interface Held {
  snapshot: Snapshot;
  serverTime: number;
  transit: number;
}

function emptyFrame(): PlayoutFrame {
  return { status: "empty", serverTime: 0, lag: 0, extrapolated: 0, newestTick: 0, bodies: [] };
}

function finiteVec(v: Vec2): boolean {
  return Number.isFinite(v.x) && Number.isFinite(v.y);
}

function advance(p: Vec2, v: Vec2, seconds: number): Vec2 {
  return { x: p.x + v.x * seconds, y: p.y + v.y * seconds };
}

function lerp(a: Vec2, b: Vec2, u: number): Vec2 {
  return { x: a.x + (b.x - a.x) * u, y: a.y + (b.y - a.y) * u };
}

function sameState(a: BodyState, b: BodyState): boolean {
  return (
    a.bodyId === b.bodyId &&
    Object.is(a.position.x, b.position.x) &&
    Object.is(a.position.y, b.position.y) &&
    Object.is(a.velocity.x, b.velocity.x) &&
    Object.is(a.velocity.y, b.velocity.y)
  );
}

export class PlayoutBuffer {
  readonly settings: PlayoutSettings;
  readonly stats: PlayoutStats = {
    accepted: 0,
    stale: 0,
    badTime: 0,
    badState: 0,
    resets: 0,
    clockBackwards: 0,
    snaps: 0,
    dropped: 0,
  };
  private held: Held[] = [];
  private stillIds = new Set<bigint>();
  private offset_ = 0;
  private jitter_ = 0;
  private lastArrival: number | undefined;
  private lastNow: number | undefined;
  private shown: number | undefined;
  private frame: PlayoutFrame = emptyFrame();

  /** Throws when a setting is out of range (validatePlayoutSettings). */
  constructor(settings: Partial<PlayoutSettings> = {}) {
    this.settings = { ...defaultPlayoutSettings(), ...settings };
    const problem = validatePlayoutSettings(this.settings);
    if (problem) throw new RangeError(`PlayoutSettings: ${problem}`);
  }

  get size(): number {
    return this.held.length;
  }
  get jitter(): number {
    return this.jitter_;
  }
  get offset(): number {
    return this.offset_;
  }
  /** The newest snapshot held, for what is not interpolated (tick, shapes, events). */
  get newest(): Snapshot | undefined {
    return this.held.length ? this.held[this.held.length - 1].snapshot : undefined;
  }

  /** The delay the shown time is steered to (s). */
  delay(): number {
    const wanted = this.settings.sendIntervals * this.interval() + this.settings.jitterMultiplier * this.jitter_;
    return Math.min(Math.max(wanted, this.settings.minDelay), this.settings.maxDelay);
  }

  push(snapshot: Snapshot, arrivalTime: number): PushResult {
    if (!Number.isFinite(arrivalTime)) {
      this.stats.badTime += 1;
      return "bad-time";
    }
    for (const body of snapshot.bodies) {
      if (!finiteVec(body.position) || !finiteVec(body.velocity)) {
        this.stats.badState += 1;
        return "bad-state";
      }
    }
    const newest = this.held[this.held.length - 1];
    if (newest && snapshot.tick <= newest.snapshot.tick) {
      this.stats.stale += 1;
      return "stale";
    }
    if (this.lastArrival !== undefined && arrivalTime < this.lastArrival) {
      this.stats.clockBackwards += 1;
      arrivalTime = this.lastArrival;
    }
    const serverTime = snapshot.tick / this.settings.tickRate;
    let result: PushResult = "accepted";
    if (newest && serverTime - newest.serverTime > this.settings.maxGap) {
      this.clear();
      this.stats.resets += 1;
      result = "reset";
    }
    const transit = arrivalTime - serverTime;
    const before = this.held[this.held.length - 1];
    if (before) {
      // RFC 3550, section 6.4.1: J += (|D| - J) / 16.
      this.jitter_ += (Math.abs(transit - before.transit) - this.jitter_) / 16;
    }
    const bodies = [...snapshot.bodies].sort((a, b) => (a.bodyId < b.bodyId ? -1 : a.bodyId > b.bodyId ? 1 : 0));
    this.held.push({ snapshot: { ...snapshot, bodies }, serverTime, transit });
    if (this.held.length > this.settings.capacity) {
      this.held.shift();
      this.stats.dropped += 1;
    }
    this.offset_ = Math.min(...this.held.map((h) => h.transit));

    this.stillIds.clear();
    if (this.held.length >= 2) {
      const previous = this.held[this.held.length - 2].snapshot.bodies;
      let j = 0;
      for (const body of bodies) {
        while (j < previous.length && previous[j].bodyId < body.bodyId) ++j;
        if (j < previous.length && sameState(previous[j], body)) this.stillIds.add(body.bodyId);
      }
    }
    this.lastArrival = arrivalTime;
    this.stats.accepted += 1;
    return result;
  }

  /** The world at the shown time for the caller's clock reading `now` (s). A NaN, or
   * a `now` before the previous call's, is taken as the previous call's (counted). */
  stateAt(now: number): PlayoutFrame {
    if (!Number.isFinite(now) || (this.lastNow !== undefined && now < this.lastNow)) {
      this.stats.clockBackwards += 1;
      now = this.lastNow ?? 0;
    }
    const elapsed = this.lastNow !== undefined ? now - this.lastNow : 0;
    this.lastNow = now;
    if (this.held.length === 0) {
      this.frame = emptyFrame();
      return this.frame;
    }
    const target = now - this.offset_ - this.delay();
    if (this.shown === undefined || Math.abs(target - (this.shown + elapsed)) > this.settings.snap) {
      if (this.shown !== undefined) this.stats.snaps += 1;
      this.shown = target;
    } else {
      this.shown += elapsed;
      const step = this.settings.slew * elapsed;
      this.shown += Math.min(Math.max(target - this.shown, -step), step);
    }
    this.fill(this.shown);
    this.frame.lag = now - this.offset_ - this.shown;
    return this.frame;
  }

  /** The world at a given server time (s), without the clock: for pictures of one
   * tick. Leaves the shown time that stateAt steers unchanged. */
  stateAtServerTime(serverTime: number): PlayoutFrame {
    if (this.held.length === 0) {
      this.frame = emptyFrame();
      return this.frame;
    }
    if (!Number.isFinite(serverTime)) return this.frame;
    this.fill(serverTime);
    this.frame.lag = this.held[this.held.length - 1].serverTime - serverTime;
    return this.frame;
  }

  private interval(): number {
    return this.settings.sendInterval > 0 ? this.settings.sendInterval : 1 / this.settings.tickRate;
  }

  private clear(): void {
    this.held = [];
    this.stillIds.clear();
    this.jitter_ = 0;
    this.offset_ = 0;
    this.shown = undefined;
  }

  private fill(shown: number): void {
    const frame: PlayoutFrame = emptyFrame();
    this.frame = frame;
    frame.serverTime = shown;
    const newest = this.held[this.held.length - 1];
    frame.newestTick = newest.snapshot.tick;
    const emit = (body: BodyState, position: Vec2, velocity: Vec2) =>
      frame.bodies.push({
        bodyId: body.bodyId,
        position,
        velocity,
        still: this.stillIds.has(body.bodyId),
        motion: body.motion ?? "dynamic",
      });

    if (shown > newest.serverTime) {
      const past = shown - newest.serverTime;
      frame.status = past <= this.settings.maxExtrapolation ? "extrapolating" : "holding";
      frame.extrapolated = past;
      const carried = Math.min(past, this.settings.maxExtrapolation);
      for (const body of newest.snapshot.bodies) emit(body, advance(body.position, body.velocity, carried), body.velocity);
      return;
    }
    const oldest = this.held[0];
    if (shown < oldest.serverTime) {
      frame.status = "early";
      for (const body of oldest.snapshot.bodies) emit(body, body.position, body.velocity);
      return;
    }
    // The snapshot after the shown time: the first held later than it.
    const after = this.held.findIndex((h) => shown < h.serverTime);
    if (after < 0) {
      // shown equals the newest server time exactly.
      frame.status = "interpolating";
      for (const body of newest.snapshot.bodies) emit(body, body.position, body.velocity);
      return;
    }
    const b = this.held[after];
    const a = this.held[after - 1];
    frame.status = "interpolating";
    // Over a gap of more than one send interval the earlier snapshot is carried at
    // its velocity until one interval before the later one, then interpolated.
    const start = Math.max(a.serverTime, b.serverTime - this.interval());
    const span = b.serverTime - start;
    const u = shown <= start ? 0 : (shown - start) / span;
    const carried = Math.min(shown, start) - a.serverTime;
    const to = b.snapshot.bodies;
    let j = 0;
    for (const body of a.snapshot.bodies) {
      while (j < to.length && to[j].bodyId < body.bodyId) ++j;
      const carriedTo = advance(body.position, body.velocity, carried);
      if (j === to.length || to[j].bodyId !== body.bodyId) {
        // Gone in the later snapshot: shown as the earlier one carries it, until then.
        const past = Math.min(shown - a.serverTime, this.settings.maxExtrapolation);
        emit(body, advance(body.position, body.velocity, past), body.velocity);
        continue;
      }
      emit(body, lerp(carriedTo, to[j].position, u), lerp(body.velocity, to[j].velocity, u));
    }
    // Bodies new in the later snapshot appear once the shown time reaches it.
  }
}
