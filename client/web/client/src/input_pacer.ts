// A player's input loop over a real path: inputs go out on the client's own clock,
// ahead of the server by the input delay (input_clock.ts), not one round trip after
// each snapshot, so a lockstep server keeps its tick rate at any round trip and a
// fixed-rate server applies each input at the tick it names. Pings measure the round
// trip; snapshots and their input margins keep the clock and the delay in step. The
// C++ client's client::InputPacer (docs/PROTOCOL.md 3.4).
//
//   const pacer = new InputPacer(client);  // the tick rate is Welcome.tickRate
//   for (;;) {
//     const snapshot = await pacer.poll(client.now() + 100, (tick) => ({ ax, ay }));
//     if (snapshot) draw(snapshot);
//   }
import type { Client } from "./client.js";
import { InputClock, defaultInputClockConfig } from "./input_clock.js";
import type { InputClockConfig } from "./input_clock.js";
import { ConnectionState } from "./types.js";
import type { Snapshot } from "./types.js";

export enum InputSchedule {
  /** Ahead of the server by the input delay, on the client's own clock (the default). */
  Clock = "clock",
  /** The input for T + afterSnapshotLead once the snapshot of T has arrived: a
   * lockstep server then waits a round trip for every tick. For comparison. */
  AfterSnapshot = "after-snapshot",
}

export interface PacerConfig {
  schedule: InputSchedule;
  afterSnapshotLead: number;
  /** tickRate 0 (the default) takes Welcome.tickRate. */
  clock: Partial<InputClockConfig>;
  /** Pings for the round trip, this often (ms). */
  pingIntervalMs: number;
}

export interface PacerStats {
  inputsSent: number;
  pingsSent: number;
  marginsSeen: number;
  /** Margins reported negative: the input was late. */
  lateMargins: number;
}

/** The acceleration to send for `tick`; called once per input sent, just before. */
export type InputFor = (tick: number) => { ax: number; ay: number };

/** The first inputs wait this long (ms) for the first round trip. */
const FIRST_ROUND_TRIP_WAIT_MS = 1000;

export class InputPacer {
  readonly clock: InputClock;
  readonly stats: PacerStats = { inputsSent: 0, pingsSent: 0, marginsSeen: 0, lateMargins: 0 };
  private readonly config: PacerConfig;
  private readonly lockstep: boolean;
  /** The newest tick the server is known to have stepped. */
  private newestSeen: number;
  private lastSent_: number;
  private nextNonce = 1n;
  private readonly started: number;
  private nextPing = -Infinity;

  /** `client` is connected as a player. In lockstep every tick gets an input, in
   * order; at a fixed rate only the newest tick due (an input holds until the next).
   * The pacer takes the client's pongs (Client.takePongs) for its round trips. */
  constructor(
    private readonly client: Client,
    config: Partial<PacerConfig> = {},
  ) {
    const welcome = client.welcome;
    if (!welcome) throw new Error("InputPacer: the client is not connected");
    this.config = {
      schedule: config.schedule ?? InputSchedule.Clock,
      afterSnapshotLead: config.afterSnapshotLead ?? 1,
      clock: config.clock ?? {},
      pingIntervalMs: config.pingIntervalMs ?? 250,
    };
    const clock: InputClockConfig = { ...defaultInputClockConfig, ...this.config.clock };
    if (!(clock.tickRate > 0)) clock.tickRate = welcome.tickRate;
    // An input further ahead than the server accepts would be refused.
    if (welcome.maxTicksAhead > 1) clock.maxDelay = Math.min(clock.maxDelay, welcome.maxTicksAhead - 1);
    this.clock = new InputClock(clock);
    this.lockstep = welcome.lockstep;
    this.newestSeen = welcome.currentTick;
    this.lastSent_ = welcome.currentTick;
    this.started = client.now();
    if (this.lockstep) {
      this.clock.onWaitingAt(this.newestSeen);
    } else {
      this.clock.onTickSeen(this.newestSeen, this.started);
    }
  }

  /** The newest tick an input was sent for. */
  get lastSent(): number {
    return this.lastSent_;
  }

  /** Sends what falls due until a snapshot arrives (returned, the clock fed with it),
   * or `deadline` (the client's clock, ms) passes, or the session ends (undefined;
   * the client's state says which). */
  async poll(deadline: number, input: InputFor): Promise<Snapshot | undefined> {
    const onClock = this.config.schedule === InputSchedule.Clock;
    for (;;) {
      if (this.client.state !== ConnectionState.Connected) return undefined;
      this.takePongs();
      const now = this.client.now();
      if (now >= this.nextPing) {
        if (!this.client.sendPing(this.nextNonce++)) return undefined;
        this.stats.pingsSent += 1;
        this.nextPing = now + this.config.pingIntervalMs;
      }
      // The first inputs wait for the first round trip (or a second without one):
      // sent before the lead is known, they would arrive late and teach the lead a
      // wrong lesson. A lockstep server waits for them anyway.
      const leadKnown = this.clock.roundTrip() !== undefined || now >= this.started + FIRST_ROUND_TRIP_WAIT_MS;
      if (!onClock || leadKnown) {
        const due = onClock ? this.clock.sendUpTo(now) : this.lastSent_;
        if (!this.sendThrough(due, input)) return undefined;
      }
      let wake = Math.min(deadline, this.nextPing);
      if (onClock) wake = Math.min(wake, this.clock.nextSendTime(now));
      const snapshot = await this.client.nextSnapshot(Math.max(0, Math.ceil(wake - now)));
      if (snapshot) {
        this.newestSeen = Math.max(this.newestSeen, snapshot.tick);
        this.clock.onTickSeen(snapshot.tick, snapshot.receivedAt);
        if (snapshot.inputMarginUs !== undefined) {
          this.stats.marginsSeen += 1;
          if (snapshot.inputMarginUs < 0) this.stats.lateMargins += 1;
          // After each snapshot the schedule is fixed: the margins have nothing to adapt.
          if (onClock) this.clock.onMargin(snapshot.inputMarginUs, snapshot.receivedAt);
        }
        if (!onClock && !this.sendThrough(snapshot.tick + this.config.afterSnapshotLead, input)) return undefined;
        return snapshot;
      }
      if (this.client.now() >= deadline) return undefined;
    }
  }

  private takePongs(): void {
    for (const pong of this.client.takePongs()) {
      if (pong.clientTimeNs === 0n) continue;
      this.clock.onRoundTrip(pong.receivedAt - Number(pong.clientTimeNs) / 1e6, pong.receivedAt);
    }
  }

  /** Sends the inputs up to `due` not sent yet: every tick in lockstep, else the newest. */
  private sendThrough(due: number, input: InputFor): boolean {
    // A lockstep server steps nothing until every player has sent the next tick.
    if (this.lockstep) due = Math.max(due, this.newestSeen + 1);
    if (due <= this.lastSent_) return true;
    // At a fixed rate an input holds until the next: only the newest due one matters.
    const first = this.lockstep ? this.lastSent_ + 1 : due;
    for (let tick = first; tick <= due; ++tick) {
      const a = input(tick);
      if (!this.client.sendInput(tick, a.ax, a.ay)) return false;
      this.stats.inputsSent += 1;
      this.lastSent_ = tick;
    }
    return true;
  }
}
