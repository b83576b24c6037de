// What one session holds of the world, as its snapshots build it: the
// reconstruction (docs/PROTOCOL.md 5) carried by the Welcome's predictor, the
// kinematic bodies, the applied-input fields that come only when they change, and
// whether the view hash still agrees with the server's. Each wire snapshot read
// becomes the Snapshot a Client hands out.
import * as wire from "./gen/wire_pb.js";
import { contactFromWire, shapeFromWire } from "./convert.js";
import { Predictor } from "./predictor.js";
import { Quantum, Reconstruction } from "./reconstruction.js";
import { BodyShape, BodyState, ClientStats, Snapshot, Welcome, findBody } from "./types.js";

export class SnapshotReader {
  private readonly reconstruction = new Reconstruction();
  /** The kinematic bodies among those sent (Welcome, Snapshot.added): each snapshot's
   * BodyState.motion comes from it. */
  private readonly kinematicIds = new Set<bigint>();
  private welcome: Welcome | undefined;
  private predictor: Predictor | undefined;
  private quantum: Quantum = { position: 0.001, velocity: 0.001 };
  private hasAppliedInput = false;
  private lastAppliedInputTick = 0;
  private inSync = true;
  /** A full state was asked for and has not come yet (the client sets it when it sent
   * the request). */
  fullStateAsked = false;

  /** askFullState: sends a request for a full state; called when the view hash differs
   * from the server's and none is asked for yet. */
  constructor(
    private readonly stats: ClientStats,
    private readonly now: () => number,
    private readonly askFullState: () => void,
  ) {}

  /** The view hash (docs/PROTOCOL.md 5.6) of what the session holds now. */
  viewHash(): bigint {
    return this.reconstruction.hash();
  }

  /** The session's Welcome: its bodies, its predictor and its precision. */
  start(welcome: Welcome): void {
    this.welcome = welcome;
    this.noteKinematic(welcome.bodies, []);
    this.predictor = new Predictor(welcome.tickRate, welcome.gravity.x, welcome.gravity.y);
    this.quantum = { position: welcome.view.positionPrecision, velocity: welcome.view.velocityPrecision };
  }

  /** The snapshot `message` makes (wireBytes: its size on the wire), or what is wrong
   * with it when it does not apply. */
  read(message: wire.Snapshot, wireBytes: number): Snapshot | string {
    // The input fields come only when they change.
    if (message.hasAppliedInput) this.hasAppliedInput = true;
    if (message.lastAppliedInputTick !== 0n) this.lastAppliedInputTick = Number(message.lastAppliedInputTick);
    const problem = this.reconstruction.apply(message, this.predictor!, this.quantum);
    if (problem) return `server sent a snapshot that does not apply: ${problem}`;
    const records =
      (message.quantized?.idGaps.length ?? 0) +
      (message.velocities?.idGaps.length ?? 0) +
      (message.exact?.idGaps.length ?? 0) +
      message.bodies.length;
    const added = message.added.map(shapeFromWire);
    const removed = [...message.removed];
    this.noteKinematic(added, removed);
    const bodies = this.bodies();
    if (message.full) {
      this.fullStateAsked = false;
      this.stats.fullStatesReceived += 1;
    }
    // The hash comes with every k-th snapshot (view_hash_interval); in between, the
    // last comparison holds.
    if (message.viewHash !== undefined) {
      this.stats.viewHashesChecked += 1;
      this.inSync = this.reconstruction.hash() === message.viewHash;
      if (!this.inSync) {
        this.stats.desyncs += 1;
        if (!this.fullStateAsked) this.askFullState();
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
      receivedAt: this.now(),
      wireBytes,
    };
    if (this.welcome && !this.welcome.spectator) snapshot.own = findBody(snapshot, this.welcome.bodyId);
    return snapshot;
  }

  private noteKinematic(added: BodyShape[], removed: bigint[]): void {
    for (const id of removed) this.kinematicIds.delete(id);
    for (const shape of added) if (shape.motion === "kinematic") this.kinematicIds.add(shape.bodyId);
  }

  /** The bodies held, as BodyStates. */
  private bodies(): BodyState[] {
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
    return bodies;
  }
}
