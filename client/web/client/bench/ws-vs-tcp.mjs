// The WebSocket port against the TCP port, with one client program for both: N
// clients of this package's Client in one node process, over the `ws` package's
// WebSocket (case ws) or over a plain TCP connection with the varint framing
// (bench/tcp-socket.mjs, case tcp). For each case, a physics-server of its own:
//   physics-server --scene SCENE --port 0 --ws-port 0 --metrics-port 0 (and the
//   per-address limits lifted, since every client comes from 127.0.0.1)
// Each client connects (default view), then for every snapshot: takes it (which
// sends its Ack) and sends an Input for the next tick, its acceleration turning on a
// circle as physics-client --bots does (5 m/s^2, one turn in 120 ticks, each client
// a phase of its own). After WARMUP s with every client joined, the server's
// counters and CPU time are read, again SECONDS s later, and the differences are
// divided by the ticks stepped in between:
//   bytes_sent, bytes_received   /metrics physics_bytes_*_total: bytes written to and
//                                read from the sockets, WebSocket frame headers and
//                                masks included
//   server_cpu_ms                utime+stime of the server process (/proc/PID/stat)
//   payload_sent, payload_received   the same two directions counted by the clients
//                                (ClientStats: message bytes, without framing)
//   framing_per_message          (bytes_sent - payload_received) per snapshot received:
//                                the frame header of a message from the server
//   snapshots                    physics_snapshots_sent_total per tick (N when every
//                                client keeps up)
//   late_inputs, skipped          per tick: inputs that came after their tick,
//                                snapshots skipped for a full window
//   client_cpu_ms                this node process's CPU time (all N clients)
// The cases take turns (tcp then ws, then ws then tcp, ...) for ROUNDS rounds; a last
// row per metric is ws/tcp, the ratio of the sums over the rounds.
// Usage: node bench/ws-vs-tcp.mjs SERVER SCENE CSV [CLIENTS SECONDS WARMUP ROUNDS]
import { spawn } from "node:child_process";
import { execFileSync } from "node:child_process";
import { readFileSync, writeFileSync } from "node:fs";
import { get as httpGet } from "node:http";
import { createInterface } from "node:readline";
import { setTimeout as sleep } from "node:timers/promises";
import WebSocket from "ws";
import { Client, ConnectionState } from "../dist/index.js";
import { TcpSocket } from "./tcp-socket.mjs";

const [server, scene, csv] = process.argv.slice(2, 5);
if (!server || !scene || !csv) {
  console.error("usage: node bench/ws-vs-tcp.mjs SERVER SCENE CSV [CLIENTS SECONDS WARMUP ROUNDS]");
  process.exit(2);
}
const [clients, seconds, warmup, rounds] = [5, 6, 7, 8].map((i, k) => Number(process.argv[i] ?? [64, 20, 3, 2][k]));
const clockTicks = Number(execFileSync("getconf", ["CLK_TCK"]).toString().trim());
const acceleration = 5;

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

async function drive(client, index, running) {
  const phase = (2 * Math.PI * index) / clients;
  while (running.on) {
    const snapshot = await client.nextSnapshot(500);
    if (!snapshot) {
      if (client.state !== ConnectionState.Connected) return;
      continue;
    }
    const tick = snapshot.tick + 1;
    const angle = phase + (2 * Math.PI * (tick % 120)) / 120;
    client.sendInput(tick, acceleration * Math.cos(angle), acceleration * Math.sin(angle));
  }
}

async function sample(srv, all) {
  const m = await metrics(srv.ports.metrics);
  const sum = (key) => all.reduce((total, c) => total + c.stats[key], 0);
  return {
    ticks: m.physics_ticks_total,
    sent: m.physics_bytes_sent_total,
    received: m.physics_bytes_received_total,
    snapshots: m.physics_snapshots_sent_total,
    skipped: m.physics_snapshots_skipped_total,
    late: m.physics_late_inputs_total,
    playing: m['physics_clients{state="playing"}'],
    serverCpu: processCpuMs(srv.pid),
    clientCpu: ownCpuMs(),
    payloadSent: sum("bytesSent"),
    payloadReceived: sum("bytesReceived"),
    snapshotsReceived: sum("snapshotsReceived"),
    wall: performance.now(),
  };
}

async function runCase(kind) {
  const srv = await startServer();
  const url = kind === "ws" ? `ws://127.0.0.1:${srv.ports.websocket}/` : `tcp://127.0.0.1:${srv.ports.listening}`;
  const Impl = kind === "ws" ? WebSocket : TcpSocket;
  const all = Array.from({ length: clients }, (_, i) => new Client({ url, WebSocket: Impl, name: `${kind}-${i}` }));
  const joined = await Promise.all(all.map((c) => c.connect(10000)));
  const failed = joined.filter((ok) => !ok).length;
  if (failed > 0) {
    const why = all.find((c) => c.state !== ConnectionState.Connected).lastError.detail;
    await srv.stop();
    throw new Error(`${kind}: ${failed} of ${clients} clients did not connect: ${why}`);
  }
  const running = { on: true };
  const loops = all.map((c, i) => drive(c, i, running));
  await sleep(warmup * 1000);
  const a = await sample(srv, all);
  await sleep(seconds * 1000);
  const b = await sample(srv, all);
  running.on = false;
  await Promise.all(loops);
  const lost = all.filter((c) => c.state !== ConnectionState.Connected).length;
  for (const c of all) c.disconnect();
  await srv.stop();
  if (lost > 0) throw new Error(`${kind}: ${lost} clients lost their connection during the run: ${all.find((c) => c.state !== ConnectionState.Connected).lastError.detail}\n${srv.log()}`);
  const d = Object.fromEntries(Object.keys(a).map((k) => [k, b[k] - a[k]]));
  return { kind, playing: b.playing, d };
}

const columns = [
  ["bytes_sent_per_tick", (d) => d.sent / d.ticks],
  ["bytes_received_per_tick", (d) => d.received / d.ticks],
  ["server_cpu_ms_per_tick", (d) => d.serverCpu / d.ticks],
  ["payload_sent_per_tick", (d) => d.payloadReceived / d.ticks],
  ["payload_received_per_tick", (d) => d.payloadSent / d.ticks],
  ["framing_per_message", (d) => (d.sent - d.payloadReceived) / d.snapshotsReceived],
  ["snapshots_per_tick", (d) => d.snapshots / d.ticks],
  ["late_inputs_per_tick", (d) => d.late / d.ticks],
  ["skipped_per_tick", (d) => d.skipped / d.ticks],
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
