// The predictor, the reconstruction and the view hash against the worked examples
// of docs/PROTOCOL.md 5.7: every value is computed here and found on the page.
import { test } from "node:test";
import assert from "node:assert/strict";
import { create, fromBinary } from "@bufbuild/protobuf";
import { Fnv64, Predictor, PredictorMode, Reconstruction, doubleBits, wire } from "../dist/index.js";
import { hex64, payloadOf, protocolDoc, wireBytesOnPage } from "./doc.mjs";

const quantum = { position: 0.001, velocity: 0.001 };

function onPage(value) {
  assert.ok(protocolDoc.includes(value), `${value} is not on docs/PROTOCOL.md`);
}

function bits(x) {
  return hex64(doubleBits(x));
}

function decodeSnapshot(frame) {
  const message = fromBinary(wire.ServerMessageSchema, payloadOf(frame));
  assert.equal(message.kind.case, "snapshot");
  return message.kind.value;
}

test("the predictor's two Ballistic steps of the worked example", () => {
  const predictor = new Predictor(60, 0, -9.81);
  onPage(`\`dt = 1.0 / 60.0\` is \`${bits(predictor.dt)}\``);
  onPage(`\`h = (0.5 * dt) * dt\` is \`${bits(predictor.halfDtSquared)}\``);
  const body = { id: 7n, idHi: 0, idLo: 7, x: 1.5, y: 2.0, vx: 3.0, vy: 4.0, mode: PredictorMode.Ballistic };
  predictor.advance(body);
  assert.equal(bits(body.x), "0x3ff8cccccccccccd");
  onPage(`| tick 11 | 1.55 (\`${bits(body.x)}\`) | \`${bits(body.y)}\` | 3.0 | \`${bits(body.vy)}\` |`);
  predictor.advance(body);
  onPage(`| tick 12 | 1.6 (\`${bits(body.x)}\`) | \`${bits(body.y)}\` | 3.0 | \`${bits(body.vy)}\` |`);
});

test("the quantized record of tick 12 gives the page's state and view hash", () => {
  const predictor = new Predictor(60, 0, -9.81);
  const held = new Reconstruction();
  // The snapshot of tick 10: one exact record, body 7, mode Ballistic (no entry).
  const tick10 = create(wire.SnapshotSchema, {
    tick: 10n,
    exact: { idGaps: [7n], x: [1.5], y: [2.0], vx: [3.0], vy: [4.0] },
  });
  assert.equal(held.apply(tick10, predictor, quantum), "");
  const frame = wireBytesOnPage("1f 12 1d");
  const snapshot = decodeSnapshot(frame);
  assert.equal(snapshot.tick, 12n);
  assert.deepEqual(snapshot.quantized.dx, [12n]);
  assert.deepEqual(snapshot.quantized.dvy, [-164n]);
  assert.equal(held.apply(snapshot, predictor, quantum), "");
  const body = held.find(7n);
  onPage(
    `| the record | \`${bits(body.x)}\` (1.612) | \`${bits(body.y)}\` | 3.0 (\`${bits(body.vx)}\`) | \`${bits(body.vy)}\` (3.509) |`,
  );
  assert.equal(body.mode, PredictorMode.Ballistic);
  assert.equal(held.hash(), snapshot.viewHash);
  onPage(`The view hash after it is \`${hex64(held.hash())}\``);
});

test("the modes example: a full state of four bodies, three lists' mode entries", () => {
  const predictor = new Predictor(60, 0, -9.81);
  const held = new Reconstruction();
  const snapshot = decodeSnapshot(wireBytesOnPage("43 12 41"));
  assert.equal(snapshot.full, true);
  assert.equal(held.apply(snapshot, predictor, quantum), "");
  const state = held.bodies().map((b) => [b.id, b.x, b.y, b.vx, b.vy, b.mode]);
  assert.deepEqual(state, [
    [3n, 1.0, 2.0, 0, 0, PredictorMode.Ballistic],
    [7n, -1.5, 0.5, 0.25, 0, PredictorMode.Glide],
    [9n, 3.0, 0.1, 0, 0, PredictorMode.Hold],
    [12n, 0, 0, -0.04, 0.01, PredictorMode.Hold],
  ]);
  onPage(`0.1 (\`${bits(held.find(9n).y)}\`)`);
  onPage(`-0.04 (\`${bits(held.find(12n).vx)}\`), 0.01 (\`${bits(held.find(12n).vy)}\`)`);
  assert.equal(held.hash(), snapshot.viewHash);
  onPage(`The view hash after it is \`${hex64(held.hash())}\``);
});

test("a client that holds nothing hashes to the FNV-1a basis", () => {
  assert.equal(new Reconstruction().hash(), 0xcbf29ce484222325n);
  onPage("hashes to `0xcbf29ce484222325`");
});

test("Fnv64 equals FNV-1a over 64-bit words computed with BigInt", () => {
  const words = [0n, 1n, 0xffffffffffffffffn, 0x123456789abcdef0n, 0x8000000000000000n, doubleBits(-0.04)];
  let reference = 0xcbf29ce484222325n;
  const h = new Fnv64();
  for (const word of words) {
    reference = BigInt.asUintN(64, (reference ^ word) * 0x100000001b3n);
    h.mix(Number(word >> 32n), Number(word & 0xffffffffn));
    assert.equal(h.value(), reference);
  }
});

test("snapshots that do not apply are refused and change nothing", () => {
  const predictor = new Predictor(60, 0, -9.81);
  const held = new Reconstruction();
  assert.equal(held.apply(create(wire.SnapshotSchema, { tick: 5n, exact: { idGaps: [4n], x: [1], y: [2], vx: [0], vy: [0] } }), predictor, quantum), "");
  const before = held.hash();
  const bad = [
    [{ tick: 4n }, /before the last/],
    [{ tick: 5n + (1n << 22n) + 1n }, /jumps/],
    [{ tick: 6n, quantized: { idGaps: [1n, 0n], dx: [0n, 0n], dy: [0n, 0n], dvx: [0n, 0n], dvy: [0n, 0n] } }, /do not ascend/],
    [{ tick: 6n, quantized: { idGaps: [1n], dx: [0n], dy: [], dvx: [0n], dvy: [0n] } }, /different lengths/],
    [{ tick: 6n, exact: { idGaps: [1n], x: [1], y: [NaN], vx: [0], vy: [0] } }, /not finite/],
    [{ tick: 6n, velocities: { idGaps: [1n], dvx: [0n], dvy: [0n], modes: [3] } }, /mode out of range/],
    [{ tick: 6n, velocities: { idGaps: [1n], dvx: [0n], dvy: [0n], modes: [1 << 2] } }, /names no record/],
    [{ tick: 6n, leftGaps: [3n, 0n] }, /do not ascend/],
  ];
  for (const [fields, why] of bad) {
    assert.match(held.apply(create(wire.SnapshotSchema, fields), predictor, quantum), why);
    assert.equal(held.hash(), before);
    assert.equal(held.tick, 5n);
  }
});

test("left_gaps forget bodies; a body not held starts from zero, Ballistic", () => {
  const predictor = new Predictor(60, 0, 0);
  const held = new Reconstruction();
  const exact = { idGaps: [2n, 3n], x: [1, 2], y: [1, 2], vx: [0, 0], vy: [0, 0], modes: [2, 6] };
  assert.equal(held.apply(create(wire.SnapshotSchema, { tick: 1n, exact }), predictor, quantum), "");
  assert.deepEqual(held.bodies().map((b) => b.id), [2n, 5n]);
  const next = { tick: 2n, leftGaps: [2n], quantized: { idGaps: [9n], dx: [1000n], dy: [0n], dvx: [0n], dvy: [0n] } };
  assert.equal(held.apply(create(wire.SnapshotSchema, next), predictor, quantum), "");
  assert.deepEqual(held.bodies().map((b) => [b.id, b.x, b.mode]), [[5n, 2, PredictorMode.Hold], [9n, 1, PredictorMode.Ballistic]]);
});
