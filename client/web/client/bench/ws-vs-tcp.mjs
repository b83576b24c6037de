// The WebSocket port against the TCP port, with one client program for both: N
// clients in one node process, over the `ws` package's WebSocket (case ws) or over a
// plain TCP connection with the varint framing (bench/tcp-socket.mjs, case tcp). The
// program is bench/light-client.mjs (the default), or with CLIENT_PROGRAM=full this
// package's Client, which applies every snapshot: on this 2-core machine about
// 650 us of CPU a snapshot (8 clients) against under 100 (64 clients), too much for
// 64 clients at 60 Hz in one process. At 8 clients both give the server the same
// bytes and work.
// For each case, a physics-server of its own:
//   physics-server --scene SCENE --port 0 --ws-port 0 --metrics-port 0 (and the
//   per-address limits lifted, since every client comes from 127.0.0.1)
// The clients join 8 at a time (default view); each, for every snapshot, sends its
// Ack, then an Input for the next tick, its acceleration turning on a circle as
// physics-client --bots does (5 m/s^2, one turn in 120 ticks, each client a phase of
// its own). WARMUP s after the last joined, the counters are read, again SECONDS s
// later, and each difference is divided by the ticks stepped in between:
//   bytes_sent, bytes_received   /metrics physics_bytes_*_total: what the server
//                                wrote to and read from its sockets, WebSocket frame
//                                headers and masks included
//   server_cpu_ms                utime+stime of the server process (/proc/PID/stat)
//   snapshots                    physics_snapshots_sent_total (N when every client
//                                keeps up); skipped, late_inputs: snapshots skipped
//                                for a full window, inputs that came after their tick
//   payload_sent, payload_received   the same two directions counted by the clients:
//                                message bytes, without framing
//   framing_per_server_message, framing_per_client_message   bytes of framing a
//                                message: the clients' sockets' byte counts less
//                                the message bytes, per message received or sent
//   client_cpu_ms                this node process's CPU time (all N clients)
// The cases take turns (tcp then ws, then ws then tcp, ...) for ROUNDS rounds; the
// last row is ws/tcp, each column's ratio of the sums over the rounds.
// Usage: node bench/ws-vs-tcp.mjs SERVER SCENE CSV [CLIENTS SECONDS WARMUP ROUNDS]
import { execFileSync, spawn } from "node:child_process";
import { readFileSync, writeFileSync } from "node:fs";
import { get as httpGet } from "node:http";
import { createInterface } from "node:readline";
import { setTimeout as sleep } from "node:timers/promises";
import WebSocket from "ws";
import { Client, ConnectionState } from "../dist/index.js";
import { LightClient } from "./light-client.mjs";
import { TcpSocket } from "./tcp-socket.mjs";

const [server, scene, csv] = process.argv.slice(2, 5);
if (!server || !scene || !csv) {
  console.error("usage: node bench/ws-vs-tcp.mjs SERVER SCENE CSV [CLIENTS SECONDS WARMUP ROUNDS]");
  process.exit(2);
}
const [clients, seconds, warmup, rounds] = [5, 6, 7, 8].map((i, k) => Number(process.argv[i] ?? [64, 20, 3, 2][k]));
const clockTicks = Number(execFileSync("getconf", ["CLK_TCK"]).toString().trim());
const accel = 5;
// light (bench/light-client.mjs) or full (Client, every snapshot applied).
const program = process.env.CLIENT_PROGRAM ?? "light";
if (program !== "light" && program !== "full") {
  console.error(`CLIENT_PROGRAM is light or full, not ${program}`);
  process.exit(2);
}

async function startServer() {
  const child = spawn(
    server,
    [
      "--scene", scene, "--port", "0", "--ws-port", "0", "--metrics-port", "0",
      "--stats-interval-s", "0", "--max-clients", String(Math.max(64, clients)),
      "--max-players-per-address", "0", "--max-pending", String(Math.max(64, clients)),
      "--max-pending-per-address", String(Math.max(64, clients)), "--connects-per-second", "0",
    ],
    { stdio: ["ignore", "pipe", "pipe"] },
  );
  let stderr = "";
  child.stderr.on("data", (chunk) => {
    stderr += chunk;
  });
  const exited = new Promise((resolve) => child.on("exit", (code, signal) => resolve(code ?? signal)));
  const ports = {};
  await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`physics-server printed no ports:\n${stderr}`)), 10000);
    exited.then((code) => reject(new Error(`physics-server exited (${code}):\n${stderr}`)));
    createInterface({ input: child.stdout }).on("line", (line) => {
      const match = line.match(/^(listening|websocket|metrics) on .*:(\d+)$/);
      if (!match) return;
      ports[match[1]] = Number(match[2]);
      if (ports.listening && ports.websocket && ports.metrics) {
        clearTimeout(timer);
        resolve();
      }
    });
  });
  return {
    pid: child.pid,
    ports,
    log: () => stderr,
    async stop() {
      child.kill("SIGTERM");
      return exited;
    },
  };
}

// node:http with no agent: one connection a request, as the endpoint closes each.
function get(url) {
  return new Promise((resolve, reject) => {
    const request = httpGet(url, { agent: false }, (response) => {
      let body = "";
      response.setEncoding("utf8");
      response.on("data", (chunk) => {
        body += chunk;
      });
      response.on("end", () => resolve(body));
      response.on("error", reject);
    });
    request.on("error", reject);
    request.setTimeout(5000, () => request.destroy(new Error(`no answer from ${url}`)));
  });
}

async function metrics(port) {
  // The endpoint closes a request it has not answered within 2 s; on a busy machine
  // that happens, and the next try is answered.
  let text;
  for (let attempt = 1; text === undefined; ++attempt) {
    try {
      text = await get(`http://127.0.0.1:${port}/metrics`);
    } catch (error) {
      if (attempt === 3) throw error;
    }
  }
  const values = {};
  for (const line of text.split("\n")) {
    const match = line.match(/^([a-z_]+(?:\{[^}]*\})?) (\S+)$/);
    if (match) values[match[1]] = Number(match[2]);
  }
  return values;
}

/** utime + stime of a process, in ms. The command name may hold spaces: fields are
 * counted after its closing parenthesis. */
function processCpuMs(pid) {
  const stat = readFileSync(`/proc/${pid}/stat`, "utf8");
  const fields = stat.slice(stat.lastIndexOf(")") + 2).split(" ");
  return ((Number(fields[11]) + Number(fields[12])) * 1000) / clockTicks;
}

function ownCpuMs() {
  const { user, system } = process.cpuUsage();
  return (user + system) / 1000;
}

function acceleration(index, tick) {
  const angle = (2 * Math.PI * index) / clients + (2 * Math.PI * (tick % 120)) / 120;
  return [accel * Math.cos(angle), accel * Math.sin(angle)];
}

/** One client of either program, behind the same few calls: connect(ms) resolves
 * true once joined and starts driving; connected(), detail(), stats, stop(),
 * disconnect(). */
function makeClient(url, Transport, kind, index) {
  const name = `${kind}-${index}`;
  // The connection's own byte counts, framing included: node's net.Socket, which the
  // `ws` package's WebSocket holds as _socket.
  let socket;
  const Impl = class extends Transport {
    constructor(...args) {
      super(...args);
      socket = this;
    }
  };
  const wire = () => {
    const raw = socket._socket ?? socket;
    return { read: raw.bytesRead, written: raw.bytesWritten };
  };
  if (program === "light") {
    const c = new LightClient({
      url,
      WebSocket: Impl,
      name,
      onSnapshot: (self, tick) => self.sendInput(tick + 1, ...acceleration(index, tick + 1)),
    });
    return {
      connect: (ms) => c.connect(ms),
      connected: () => c.connected,
      detail: () => c.detail,
      stats: c.stats,
      wire,
      stop: async () => {},
      disconnect: () => c.disconnect(),
    };
  }
  const c = new Client({ url, WebSocket: Impl, name });
  let running = false;
  let loop = Promise.resolve();
  const drive = async () => {
    while (running) {
      const snapshot = await c.nextSnapshot(500);
      if (!snapshot) {
        if (c.state !== ConnectionState.Connected) return;
        continue;
      }
      c.sendInput(snapshot.tick + 1, ...acceleration(index, snapshot.tick + 1));
    }
  };
  return {
    connect: async (ms) => {
      const ok = await c.connect(ms);
      if (ok) {
        running = true;
        loop = drive();
      }
      return ok;
    },
    connected: () => c.state === ConnectionState.Connected,
    detail: () => c.lastError.detail,
    get stats() {
      return c.stats;
    },
    wire,
    stop: async () => {
      running = false;
      await loop;
    },
    disconnect: () => c.disconnect(),
  };
}

async function sample(srv, all) {
  // The clients' counts first, all in one turn of the event loop, so that they agree
  // with each other; the server's follow within a millisecond or so.
  const sum = (f) => all.reduce((total, c) => total + f(c), 0);
  const clientSide = {
    payloadSent: sum((c) => c.stats.bytesSent),
    payloadReceived: sum((c) => c.stats.bytesReceived),
    wireSent: sum((c) => c.wire().written),
    wireReceived: sum((c) => c.wire().read),
    messagesSent: sum((c) => c.stats.inputsSent + c.stats.acksSent),
    messagesReceived: sum((c) => c.stats.snapshotsReceived),
    clientCpu: ownCpuMs(),
    wall: performance.now(),
  };
  const m = await metrics(srv.ports.metrics);
  return {
    ...clientSide,
    serverCpu: processCpuMs(srv.pid),
    ticks: m.physics_ticks_total,
    sent: m.physics_bytes_sent_total,
    received: m.physics_bytes_received_total,
    snapshots: m.physics_snapshots_sent_total,
    skipped: m.physics_snapshots_skipped_total,
    late: m.physics_late_inputs_total,
    playing: m['physics_clients{state="playing"}'],
  };
}

async function runCase(kind) {
  const srv = await startServer();
  const url = kind === "ws" ? `ws://127.0.0.1:${srv.ports.websocket}/` : `tcp://127.0.0.1:${srv.ports.listening}`;
  const Impl = kind === "ws" ? WebSocket : TcpSocket;
  const all = Array.from({ length: clients }, (_, i) => makeClient(url, Impl, kind, i));
  // moving-1000 has two spawn points: a player is placed at the first free position
  // near them, and at once about 55 fit. So the clients join 8 at a time, each
  // starting to drive as soon as it joins (its body drifts off the spawn), and one
  // refused for want of room tries again half a second later.
  for (let first = 0; first < clients; first += 8) {
    const batch = all.slice(first, first + 8);
    for (let attempt = 1; ; ++attempt) {
      const waiting = batch.filter((c) => !c.connected());
      if (waiting.length === 0) break;
      await Promise.all(waiting.map((c) => c.connect(10000)));
      const refused = batch.filter((c) => !c.connected());
      if (refused.length === 0) continue;
      const why = refused[0].detail();
      if (attempt === 20 || !why.startsWith("NO_SPAWN")) {
        await Promise.all(all.map((c) => c.stop()));
        await srv.stop();
        throw new Error(`${kind}: ${refused.length} clients did not join: ${why}`);
      }
      await sleep(500);
    }
  }
  await sleep(warmup * 1000);
  const a = await sample(srv, all);
  await sleep(seconds * 1000);
  const b = await sample(srv, all);
  await Promise.all(all.map((c) => c.stop()));
  const lost = all.filter((c) => !c.connected());
  for (const c of all) c.disconnect();
  await srv.stop();
  if (lost.length > 0) {
    throw new Error(`${kind}: ${lost.length} clients lost their connection: ${lost[0].detail()}\n${srv.log()}`);
  }
  const d = Object.fromEntries(Object.keys(a).map((k) => [k, b[k] - a[k]]));
  return { kind, playing: b.playing, d };
}

const columns = [
  ["bytes_sent_per_tick", (d) => d.sent / d.ticks],
  ["bytes_received_per_tick", (d) => d.received / d.ticks],
  ["server_cpu_ms_per_tick", (d) => d.serverCpu / d.ticks],
  ["snapshots_per_tick", (d) => d.snapshots / d.ticks],
  ["skipped_per_tick", (d) => d.skipped / d.ticks],
  ["late_inputs_per_tick", (d) => d.late / d.ticks],
  ["payload_sent_per_tick", (d) => d.payloadReceived / d.ticks],
  ["payload_received_per_tick", (d) => d.payloadSent / d.ticks],
  ["framing_per_server_message", (d) => (d.wireReceived - d.payloadReceived) / d.messagesReceived],
  ["framing_per_client_message", (d) => (d.wireSent - d.payloadSent) / d.messagesSent],
  ["client_cpu_ms_per_tick", (d) => d.clientCpu / d.ticks],
];
const header = ["case", "round", "clients", "seconds", "ticks", ...columns.map(([name]) => name)];
const rows = [];
const totals = { tcp: {}, ws: {} };
// A ratio of two zeros (no skipped snapshots in either case) is left empty.
const digits = (x) => (Number.isFinite(x) ? x.toFixed(3) : "");
console.error(`ws-vs-tcp: ${clients} clients, ${seconds} s after ${warmup} s, ${rounds} rounds, ${scene}`);
for (let round = 1; round <= rounds; ++round) {
  for (const kind of round % 2 === 1 ? ["tcp", "ws"] : ["ws", "tcp"]) {
    const { playing, d } = await runCase(kind);
    for (const [k, v] of Object.entries(d)) totals[kind][k] = (totals[kind][k] ?? 0) + v;
    const row = [kind, round, playing, (d.wall / 1000).toFixed(1), d.ticks, ...columns.map(([, f]) => digits(f(d)))];
    console.error(`ws-vs-tcp: ${header.map((h, i) => `${h}=${row[i]}`).join(" ")}`);
    rows.push(row);
  }
}
const ratio = (f) => f(totals.ws) / f(totals.tcp);
rows.push(["ws/tcp", "all", clients, "", "", ...columns.map(([, f]) => digits(ratio(f)))]);
const text = [header, ...rows].map((r) => r.join(",")).join("\n") + "\n";
writeFileSync(csv, text);
process.stdout.write(text);
