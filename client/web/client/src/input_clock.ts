// When a player sends the input for which tick: the client's estimate of the server's
// tick, and the input delay (docs/PROTOCOL.md 3.4, "Input delay"). Inputs are sent
// ahead of the server by a lead of about the one-way delay plus the jitter, so that
// each arrives just before its tick is due. The server reports in each snapshot how
// early the client's inputs arrived (Snapshot.inputMarginUs); the lead grows at once
// when one arrives with less than `safetyMs` to spare, and shrinks by half the spare
// while every input of a second arrived with more. The C++ client's
// client::InputClock, in milliseconds. No sockets, no clock: time is passed in.

export interface InputClockConfig {
  /** Welcome.tickRate (InputPacer fills it in when 0). */
  tickRate: number;
  /** Ticks ahead of the server's tick that inputs are sent for. Unset: chosen from
   * the round trip and adapted to the margins the server reports. */
  fixedDelay?: number;
  /** The least margin the adaptive lead keeps above the worst arrival (ms). */
  safetyMs: number;
  /** The largest delay, in ticks (keep it below Welcome.maxTicksAhead). */
  maxDelay: number;
}

export const defaultInputClockConfig: Readonly<InputClockConfig> = { tickRate: 0, safetyMs: 2, maxDelay: 100 };

/** Round trips are remembered this long (ms); the least of them is the round trip. */
const TRIP_MEMORY_MS = 2000;
const MAX_TRIPS = 256;
/** How fast the arrival offset follows a later one: 1/16 of the difference a
 * snapshot (about a quarter second at 60 Hz). */
const OFFSET_RISE = 16;
/** The lead is lowered at most once a window (ms). */
const LOWER_WINDOW_MS = 1000;

interface Trip {
  received: number;
  roundTrip: number;
}

export class InputClock {
  private readonly config: InputClockConfig;
  readonly periodMs: number;
  private baseTick: number | undefined;
  /** When tick baseTick was seen, of the least delayed snapshots (see onTickSeen). */
  private offset: number | undefined;
  private trips: Trip[] = [];
  private waitingAt: number | undefined;
  /** Inputs are sent this far ahead of the tick seen (ms): adaptive. Kept against
   * the tick seen, not the server's, so that a round trip that changes moves it only
   * through the margins, never twice. */
  private aheadMs = 0;
  private leadChosen: boolean;
  /** Raising waits a round trip after the last raise: the margins reported meanwhile
   * are of inputs sent before it. */
  private raiseSettles = -Infinity;
  private lowerWindowStart = 0;
  private leastInWindow: number | undefined;
  raises = 0;
  lowers = 0;

  constructor(config: Partial<InputClockConfig> = {}) {
    this.config = { ...defaultInputClockConfig, ...config };
    this.periodMs = 1000 / Math.max(this.config.tickRate, 1e-3);
    this.leadChosen = this.config.fixedDelay !== undefined;
  }

  /** The server stepped tick `tick` (a snapshot of it arrived at `received`, ms). */
  onTickSeen(tick: number, received: number): void {
    if (this.baseTick === undefined) this.baseTick = tick;
    // Ticks before the first one seen (a reordered heartbeat) count as negative.
    const offset = received - (tick - this.baseTick) * this.periodMs;
    // An earlier arrival is taken at once (jitter and queueing only add delay); a
    // later one is followed slowly, so that jitter barely moves the estimate and a
    // server that fell behind is followed within a quarter second.
    if (this.offset === undefined || offset < this.offset) {
      this.offset = offset;
    } else {
      this.offset += (offset - this.offset) / OFFSET_RISE;
    }
    this.waitingAt = undefined;
  }

  /** The server is at `tick` and steps only when inputs arrive (a lockstep Welcome):
   * until a tick is seen stepped, its tick is taken to stand still there. */
  onWaitingAt(tick: number): void {
    if (this.offset === undefined) this.waitingAt = tick;
  }

  /** A Ping's round trip (ms), answered at `received`. */
  onRoundTrip(roundTrip: number, received: number): void {
    if (!(roundTrip >= 0)) return;
    this.trips.push({ received, roundTrip });
    while (
      this.trips.length > MAX_TRIPS ||
      (this.trips.length > 1 && this.trips[0].received + TRIP_MEMORY_MS < received)
    ) {
      this.trips.shift();
    }
    if (!this.leadChosen) {
      // A whole round trip ahead of the tick seen is half of one ahead of the server
      // on a symmetric path; the margins the server reports correct what that misses.
      this.aheadMs = Math.min(roundTrip + this.config.safetyMs, this.maxAhead());
      this.leadChosen = true;
      this.lowerWindowStart = received;
    }
  }

  /** Snapshot.inputMarginUs, in a snapshot that arrived at `received`. */
  onMargin(marginUs: number, received: number): void {
    if (this.config.fixedDelay !== undefined || !this.leadChosen) return;
    const margin = marginUs / 1000;
    const safety = this.config.safetyMs;
    if (margin < safety) {
      if (received >= this.raiseSettles) {
        this.aheadMs = Math.min(this.aheadMs + (safety - margin), this.maxAhead());
        this.raises += 1;
        this.raiseSettles = received + (this.roundTrip() ?? 0) + 2 * this.periodMs;
      }
      this.lowerWindowStart = received;
      this.leastInWindow = undefined;
      return;
    }
    if (this.leastInWindow === undefined || margin < this.leastInWindow) this.leastInWindow = margin;
    if (received - this.lowerWindowStart < LOWER_WINDOW_MS) return;
    // Every input of the window arrived with more than an eighth of a tick to spare:
    // give back half of the spare.
    const spare = this.leastInWindow - safety;
    if (spare > this.periodMs / 8) {
      this.aheadMs = Math.max(0, this.aheadMs - spare / 2);
      this.lowers += 1;
    }
    this.lowerWindowStart = received;
    this.leastInWindow = undefined;
  }

  /** The least round trip of the last two seconds (ms), once one was measured. */
  roundTrip(): number | undefined {
    if (this.trips.length === 0) return undefined;
    let least = this.trips[0].roundTrip;
    for (const trip of this.trips) least = Math.min(least, trip.roundTrip);
    return least;
  }

  /** The server's tick at `now`, with its fraction: the tick it last stepped plus the
   * time since, from the least delayed of the recent snapshots. */
  serverTick(now: number): number {
    if (this.offset === undefined) return this.waitingAt ?? 0;
    return this.seenTick(now) + this.oneWay() / this.periodMs;
  }

  /** The newest tick whose input is due to be sent by `now`. */
  sendUpTo(now: number): number {
    const tick = this.sendPosition(now);
    return tick <= 0 ? 0 : Math.floor(tick);
  }

  /** When sendUpTo() next grows (at most one tick period after `now`). */
  nextSendTime(now: number): number {
    if (this.offset === undefined) return now + this.periodMs;
    const tick = this.sendPosition(now);
    return now + (Math.floor(tick) + 1 - tick) * this.periodMs;
  }

  /** The lead in ticks, rounded up: inputs name the server's tick plus this. */
  delay(): number {
    return Math.ceil(this.lead() / this.periodMs - 1e-9);
  }

  /** How far ahead of the server's tick inputs are sent (ms): half a round trip less
   * than ahead of the tick last seen. */
  lead(): number {
    return Math.max(0, this.ahead() - this.oneWay());
  }

  private oneWay(): number {
    const trip = this.roundTrip();
    return trip === undefined ? 0 : trip / 2;
  }

  private maxAhead(): number {
    return this.periodMs * this.config.maxDelay + this.oneWay();
  }

  private ahead(): number {
    const fixed = this.config.fixedDelay;
    if (fixed !== undefined) return this.periodMs * Math.min(fixed, this.config.maxDelay) + this.oneWay();
    return this.aheadMs;
  }

  private seenTick(now: number): number {
    return this.baseTick! + (now - this.offset!) / this.periodMs;
  }

  // Where the inputs sent by `now` reach: the tick seen plus the round trip and
  // margin, or, while a lockstep server waits, its tick plus the lead.
  private sendPosition(now: number): number {
    if (this.offset === undefined) return this.serverTick(now) + this.lead() / this.periodMs;
    return this.seenTick(now) + this.ahead() / this.periodMs;
  }
}
