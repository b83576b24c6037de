// The bodies a client holds, rebuilt from snapshots (docs/PROTOCOL.md 5.3 to 5.6): a
// port of the server's own (shared/wire/src/reconstruction.cpp), which keeps a mirror
// of each client built by the same steps, so that the view hash compares bits.
import type { Snapshot as WireSnapshot } from "./gen/wire_pb.js";
import { Fnv64, bigintWords } from "./words.js";
import { PREDICTOR_MODE_COUNT, PredictedBody, Predictor, PredictorMode } from "./predictor.js";

/** A snapshot may carry the bodies this far ahead of the last one (a hostile server
 * cannot make a client step forever). */
export const MAX_TICK_GAP = 1n << 22n;

/** The quanta of quantized records: an integer n stands for n * quantum. */
export interface Quantum {
  position: number;
  velocity: number;
}

const enum RecordKind {
  Quantized,
  Velocity,
  Exact,
}

interface BodyRecord {
  id: bigint;
  kind: RecordKind;
  /** Exact: the value; quantized and velocity: the integer, as a double. */
  x: number;
  y: number;
  vx: number;
  vy: number;
  mode: PredictorMode | undefined;
}

/** Thrown (and caught by apply) when a snapshot is not one a server could send. */
class BadSnapshot extends Error {}

/** Ascending ids sent as gaps (the first gap is the id itself). */
export function decodeIdGaps(gaps: readonly bigint[], what: string): bigint[] {
  const ids: bigint[] = new Array(gaps.length);
  let id = 0n;
  for (let i = 0; i < gaps.length; ++i) {
    const gap = gaps[i];
    if (i > 0 && gap === 0n) throw new BadSnapshot(`${what} ids do not ascend`);
    id += gap;
    if (id > 0xffffffffffffffffn) throw new BadSnapshot(`${what} ids do not ascend`);
    ids[i] = id;
  }
  return ids;
}

// (gap << 2) | mode, the gap being the record's index minus the index the entry
// before named (the first: the index itself).
function readModes(modes: readonly number[], count: number, first: number, records: BodyRecord[]) {
  let index = 0;
  modes.forEach((entry, n) => {
    const gap = entry >>> 2;
    const mode = entry & 3;
    if (mode >= PREDICTOR_MODE_COUNT) throw new BadSnapshot("a predictor mode out of range");
    if (n > 0 && gap === 0) throw new BadSnapshot("predictor modes are not in ascending record order");
    index += gap;
    if (index >= count) throw new BadSnapshot("a predictor mode names no record");
    records[first + index].mode = mode as PredictorMode;
  });
}

function sameLength(what: string, n: number, ...lists: { length: number }[]) {
  if (lists.some((list) => list.length !== n)) throw new BadSnapshot(`${what} lists of different lengths`);
}

function finite(...values: number[]) {
  return values.every((v) => Number.isFinite(v));
}

// One of a snapshot's record lists (quantized, velocity, exact): its ids, one record
// each from `state(i)`, and its predictor modes, which index this list alone.
function readList(
  records: BodyRecord[],
  list: { idGaps: bigint[]; modes: number[] },
  what: string,
  kind: RecordKind,
  state: (i: number) => { x: number; y: number; vx: number; vy: number },
) {
  const n = list.idGaps.length;
  const ids = decodeIdGaps(list.idGaps, what);
  const first = records.length;
  for (let i = 0; i < n; ++i) records.push({ id: ids[i], kind, ...state(i), mode: undefined });
  readModes(list.modes, n, first, records);
}

function readRecords(snapshot: WireSnapshot): BodyRecord[] {
  const records: BodyRecord[] = [];
  const q = snapshot.quantized;
  if (q) {
    sameLength("quantized body", q.idGaps.length, q.dx, q.dy, q.dvx, q.dvy);
    readList(records, q, "quantized body", RecordKind.Quantized, (i) => ({
      x: Number(q.dx[i]),
      y: Number(q.dy[i]),
      vx: Number(q.dvx[i]),
      vy: Number(q.dvy[i]),
    }));
  }
  const v = snapshot.velocities;
  if (v) {
    sameLength("velocity", v.idGaps.length, v.dvx, v.dvy);
    readList(records, v, "velocity record", RecordKind.Velocity, (i) => ({
      x: 0,
      y: 0,
      vx: Number(v.dvx[i]),
      vy: Number(v.dvy[i]),
    }));
  }
  const e = snapshot.exact;
  if (e) {
    sameLength("exact body", e.idGaps.length, e.x, e.y, e.vx, e.vy);
    readList(records, e, "exact body", RecordKind.Exact, (i) => {
      if (!finite(e.x[i], e.y[i], e.vx[i], e.vy[i])) {
        throw new BadSnapshot("an exact body state that is not finite");
      }
      return { x: e.x[i], y: e.y[i], vx: e.vx[i], vy: e.vy[i] };
    });
  }
  // ENCODING_FULL's bodies: held as sent, in mode Hold, so that the full encoding has
  // a view hash as the others do.
  let last = -1n;
  for (const body of snapshot.bodies) {
    if (body.bodyId <= last) throw new BadSnapshot("full-encoding body ids do not ascend");
    last = body.bodyId;
    if (!finite(body.x, body.y, body.vx, body.vy)) {
      throw new BadSnapshot("a full-encoding body state that is not finite");
    }
    records.push({ id: body.bodyId, kind: RecordKind.Exact, x: body.x, y: body.y, vx: body.vx, vy: body.vy, mode: PredictorMode.Hold });
  }
  return records;
}

function newBody(id: bigint): PredictedBody {
  const [idHi, idLo] = bigintWords(id);
  return { id, idHi, idLo, x: 0, y: 0, vx: 0, vy: 0, mode: PredictorMode.Ballistic };
}

// A record applied to what the client holds (a body not held starts from zero,
// Ballistic): quantized x = x_held + n * quantum; velocity the same for vx, vy alone;
// exact x = the value.
function applyRecord(body: PredictedBody, r: BodyRecord, q: Quantum): void {
  switch (r.kind) {
    case RecordKind.Exact:
      body.x = r.x;
      body.y = r.y;
      body.vx = r.vx;
      body.vy = r.vy;
      break;
    case RecordKind.Quantized:
      body.x = body.x + r.x * q.position;
      body.y = body.y + r.y * q.position;
      body.vx = body.vx + r.vx * q.velocity;
      body.vy = body.vy + r.vy * q.velocity;
      break;
    case RecordKind.Velocity:
      body.vx = body.vx + r.vx * q.velocity;
      body.vy = body.vy + r.vy * q.velocity;
      break;
  }
  if (r.mode !== undefined) body.mode = r.mode;
}

export class Reconstruction {
  private held: PredictedBody[] = [];
  private tick_ = 0n;
  private started_ = false;

  /**
   * Applies one snapshot: `full` forgets first; every body held is advanced to the
   * snapshot's tick; the bodies of left_gaps go; the records replace or add bodies.
   * Returns "" on success, or what is wrong with the snapshot; nothing changes then
   * (everything is read and checked first).
   */
  apply(snapshot: WireSnapshot, predictor: Predictor, quantum: Quantum): string {
    let records: BodyRecord[];
    let gone: bigint[];
    try {
      if (this.started_ && !snapshot.full && snapshot.tick < this.tick_) {
        throw new BadSnapshot(`snapshot tick ${snapshot.tick} is before the last, ${this.tick_}`);
      }
      if (this.started_ && !snapshot.full && snapshot.tick - this.tick_ > MAX_TICK_GAP) {
        throw new BadSnapshot(`snapshot tick jumps by more than ${MAX_TICK_GAP} ticks`);
      }
      records = readRecords(snapshot);
      gone = decodeIdGaps(snapshot.leftGaps, "left body");
    } catch (error) {
      if (error instanceof BadSnapshot) return error.message;
      throw error;
    }
    // One list by id; the sort is stable, so a body in several lists takes its
    // records in the order quantized, velocity, exact, full.
    records.sort((a, b) => (a.id < b.id ? -1 : a.id > b.id ? 1 : 0));

    if (snapshot.full) this.clear();
    if (!this.started_) {
      this.tick_ = snapshot.tick;
      this.started_ = true;
    }
    this.advanceTo(snapshot.tick, predictor);

    // Merge, as the server's mirror does: a body held that has records and is named
    // in left_gaps goes; a body not held takes its records from zero.
    const next: PredictedBody[] = [];
    let r = 0;
    let g = 0;
    const pushNew = () => {
      // Two records of one body not held: each applies to zero and the last is kept,
      // as in the server's mirror.
      const id = records[r].id;
      let body = newBody(id);
      applyRecord(body, records[r++], quantum);
      while (r < records.length && records[r].id === id) {
        body = newBody(id);
        applyRecord(body, records[r++], quantum);
      }
      next.push(body);
    };
    for (const held of this.held) {
      while (r < records.length && records[r].id < held.id) pushNew();
      while (g < gone.length && gone[g] < held.id) ++g;
      const leaves = g < gone.length && gone[g] === held.id;
      while (r < records.length && records[r].id === held.id) applyRecord(held, records[r++], quantum);
      if (!leaves) next.push(held);
    }
    while (r < records.length) pushNew();
    this.held = next;
    return "";
  }

  /** Advances every body one predictor step per tick up to `tick`. */
  advanceTo(tick: bigint, predictor: Predictor): void {
    if (tick <= this.tick_) return;
    const steps = Number(tick - this.tick_);
    for (const body of this.held) {
      if (body.mode === PredictorMode.Hold) continue;
      for (let i = 0; i < steps; ++i) predictor.advance(body);
    }
    this.tick_ = tick;
  }

  clear(): void {
    this.held = [];
    this.started_ = false;
    this.tick_ = 0n;
  }

  get tick(): bigint {
    return this.tick_;
  }

  get started(): boolean {
    return this.started_;
  }

  /** The bodies held, ascending id. Read only: they change with the next apply. */
  bodies(): readonly PredictedBody[] {
    return this.held;
  }

  find(id: bigint): PredictedBody | undefined {
    let lo = 0;
    let hi = this.held.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.held[mid].id < id) lo = mid + 1;
      else hi = mid;
    }
    return lo < this.held.length && this.held[lo].id === id ? this.held[lo] : undefined;
  }

  /** The view hash (docs/PROTOCOL.md 5.6) of what is held. */
  hash(): bigint {
    const h = new Fnv64();
    for (const b of this.held) {
      h.mix(b.idHi, b.idLo);
      h.mixDouble(b.x);
      h.mixDouble(b.y);
      h.mixDouble(b.vx);
      h.mixDouble(b.vy);
      h.mix(0, b.mode);
    }
    return h.value();
  }
}
