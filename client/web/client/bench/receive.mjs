// What a snapshot costs the client to receive, in node (V8, Chromium's engine): a
// world of N bodies in free flight held in the predicted encoding, and 600
// snapshots each carrying R quantized records, with and without a view hash. Times
// are CPU microseconds per snapshot (user + system of the process, so that a shared
// machine's waiting is left out), the median of REPEATS runs (default 5) taken in
// turns after one run not counted:
//   decode  fromBinary of the ServerMessage alone
//   apply   Reconstruction.apply alone (advance every body held one tick, merge)
//   hash    Reconstruction.hash alone (the view hash of every body held)
//   client  the whole path through Client: decode, apply, hash when carried, the
//           plain Snapshot (every body held), taking it and its Ack
// Prints CSV on stdout: bodies,records,view_hash,decode_us,apply_us,hash_us,client_us.
import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import { Client, Predictor, Reconstruction, wire } from "../dist/index.js";

const repeats = Number(process.env.REPEATS ?? 5);
const snapshots = 600;
const quantum = { position: 0.001, velocity: 0.001 };

function lcg(seed) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 4294967296;
  };
}

// The messages: a full state of n bodies, then `snapshots` of r records each; their
// view hashes computed by a reconstruction of their own, so that the client agrees.
function messages(n, r, withHash) {
  const random = lcg(n * 7919 + r);
  const predictor = new Predictor(60, 0, -9.81);
  const mirror = new Reconstruction();
  const ids = Array.from({ length: n }, (_, i) => (1n << 32n) | BigInt(i + 1));
  const out = [];
  const add = (fields) => {
    const snapshot = create(wire.SnapshotSchema, fields);
    mirror.apply(snapshot, predictor, quantum);
    if (withHash) snapshot.viewHash = mirror.hash();
    const bytes = toBinary(wire.ServerMessageSchema, create(wire.ServerMessageSchema, { kind: { case: "snapshot", value: snapshot } }));
    out.push(bytes);
  };
  const q = (count) => Array.from({ length: count }, () => BigInt(Math.round((random() - 0.5) * 2e5)));
  add({ tick: 1n, full: true, quantized: { idGaps: ids.map((id, i) => (i === 0 ? id : 1n)), dx: q(n), dy: q(n), dvx: q(n), dvy: q(n) } });
  for (let k = 0; k < snapshots; ++k) {
    const chosen = new Set();
    while (chosen.size < r) chosen.add(Math.floor(random() * n));
    const picked = [...chosen].sort((a, b) => a - b).map((i) => ids[i]);
    const small = () => Array.from({ length: r }, () => BigInt(Math.round((random() - 0.5) * 40)));
    add({
      tick: BigInt(k + 2),
      quantized: { idGaps: picked.map((id, i) => (i === 0 ? id : id - picked[i - 1])), dx: small(), dy: small(), dvx: small(), dvy: small() },
    });
  }
  return out;
}

class FakeSocket {
  static last;
  binaryType = "";
  readyState = 1;
  onopen = null;
  onmessage = null;
  onclose = null;
  onerror = null;
  constructor() {
    FakeSocket.last = this;
    queueMicrotask(() => this.onopen?.({}));
  }
  send() {}
  close() {}
}

function cpuMicros() {
  const { user, system } = process.cpuUsage();
  return user + system;
}

function perSnapshot(start, count) {
  return (cpuMicros() - start) / count;
}

function timeDecode(all) {
  const start = cpuMicros();
  for (let k = 1; k < all.length; ++k) fromBinary(wire.ServerMessageSchema, all[k]);
  return perSnapshot(start, all.length - 1);
}

function timeApplyAndHash(all) {
  const decoded = all.map((bytes) => fromBinary(wire.ServerMessageSchema, bytes).kind.value);
  const predictor = new Predictor(60, 0, -9.81);
  const held = new Reconstruction();
  held.apply(decoded[0], predictor, quantum);
  let start = cpuMicros();
  for (let k = 1; k < decoded.length; ++k) held.apply(decoded[k], predictor, quantum);
  const apply = perSnapshot(start, decoded.length - 1);
  start = cpuMicros();
  for (let k = 1; k < decoded.length; ++k) held.hash();
  return [apply, perSnapshot(start, decoded.length - 1)];
}

async function timeClient(all) {
  const client = new Client({ url: "ws://bench/", WebSocket: FakeSocket, keepaliveMs: 0 });
  const connecting = client.connect(1000);
  await new Promise((resolve) => setTimeout(resolve, 0));
  const welcome = { case: "welcome", value: { protocolVersion: 2, tickRate: 60, gravity: { x: 0, y: -9.81 }, currentTick: 0n } };
  const deliver = (bytes) => FakeSocket.last.onmessage({ data: bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length) });
  deliver(toBinary(wire.ServerMessageSchema, create(wire.ServerMessageSchema, { kind: welcome })));
  await connecting;
  deliver(all[0]);
  await client.nextSnapshot(0);
  const start = cpuMicros();
  for (let k = 1; k < all.length; ++k) {
    deliver(all[k]);
    await client.nextSnapshot(0);
  }
  const us = perSnapshot(start, all.length - 1);
  if (client.stats.desyncs !== 0) throw new Error("the client's view hash differed from the generator's");
  return us;
}

const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

console.log("bodies,records,view_hash,decode_us,apply_us,hash_us,client_us");
for (const n of [1000, 4000]) {
  for (const r of [10, 100]) {
    for (const withHash of [false, true]) {
      const all = messages(n, r, withHash);
      const runs = { decode: [], apply: [], hash: [], client: [] };
      // A first run, not counted: V8 compiles the hot functions during it.
      timeDecode(all);
      timeApplyAndHash(all);
      await timeClient(all);
      for (let i = 0; i < repeats; ++i) {
        runs.decode.push(timeDecode(all));
        const [apply, hash] = timeApplyAndHash(all);
        runs.apply.push(apply);
        runs.hash.push(hash);
        runs.client.push(await timeClient(all));
      }
      const f = (v) => median(v).toFixed(1);
      console.log([n, r, withHash ? 1 : 0, f(runs.decode), f(runs.apply), f(runs.hash), f(runs.client)].join(","));
    }
  }
}
