// physics-server as a child process for the tests: its WebSocket port read from the
// "websocket on ADDRESS:PORT" line it prints once it listens. The binary is
// $PHYSICS_SERVER, or build/server/physics-server under the repository's root. And
// physics-netsim, the link conditioner, in front of it: $PHYSICS_NETSIM, or
// build/testing/physics-netsim.
import { spawn } from "node:child_process";
import { existsSync } from "node:fs";
import { createInterface } from "node:readline";
import { repoRoot } from "./doc.mjs";

export const serverBinary = process.env.PHYSICS_SERVER || `${repoRoot}build/server/physics-server`;
export const netsimBinary = process.env.PHYSICS_NETSIM || `${repoRoot}build/testing/physics-netsim`;

/** Spawns `binary` with `args` and reads the "NAME on ADDRESS:PORT" lines it prints
 * until it has printed one for each of `names`; resolves to { ports, log(), stop() }
 * (ports: NAME -> { host, port }; stop(): SIGTERM, resolving to the exit code). */
async function startListening(binary, envName, args, names, timeoutMs) {
  const tool = binary.split("/").pop();
  if (!existsSync(binary)) throw new Error(`no ${tool} at ${binary}: build it, or set ${envName}`);
  const child = spawn(binary, args, { stdio: ["ignore", "pipe", "pipe"] });
  let stderr = "";
  child.stderr.on("data", (chunk) => {
    stderr += chunk;
  });
  const exited = new Promise((resolve) => child.on("exit", (code, signal) => resolve({ code, signal })));
  const lines = createInterface({ input: child.stdout });
  const ports = {};
  await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`${tool} printed no ports in ${timeoutMs} ms:\n${stderr}`)), timeoutMs);
    exited.then(({ code, signal }) => reject(new Error(`${tool} exited (${code ?? signal}) before listening:\n${stderr}`)));
    lines.on("line", (line) => {
      // An IPv6 address is printed bare: the port follows the last colon.
      const match = line.match(/^(\w+) on (.*):(\d+)$/);
      if (!match || !names.includes(match[1])) return;
      ports[match[1]] = { host: match[2], port: Number(match[3]) };
      if (names.every((name) => ports[name])) {
        clearTimeout(timer);
        resolve();
      }
    });
  });
  return {
    ports,
    log: () => stderr,
    async stop() {
      if (child.exitCode === null && child.signalCode === null) child.kill("SIGTERM");
      const { code } = await exited;
      return code;
    },
  };
}

/** Starts physics-server with `args` (plus --port 0 --ws-port 0); resolves to
 * { url, port, wsPort, stop(), log() } once it has printed both ports. */
export async function startServer(args = [], { timeoutMs = 10000 } = {}) {
  const server = await startListening(
    serverBinary,
    "PHYSICS_SERVER",
    ["--port", "0", "--ws-port", "0", "--stats-interval-s", "0", ...args],
    ["listening", "websocket"],
    timeoutMs,
  );
  const { listening, websocket } = server.ports;
  const host = websocket.host.includes(":") ? `[${websocket.host}]` : websocket.host;
  return { url: `ws://${host}:${websocket.port}/`, port: listening.port, wsPort: websocket.port, ...server };
}

/** Starts physics-netsim relaying to the server's port `targetPort` with `args` (its
 * path: --latency-ms and so on); resolves to { url, port, stop(), log() } once it
 * listens. */
export async function startNetsim(targetPort, args = [], { timeoutMs = 10000 } = {}) {
  const netsim = await startListening(
    netsimBinary,
    "PHYSICS_NETSIM",
    ["--port", "0", "--to", `127.0.0.1:${targetPort}`, ...args],
    ["listening"],
    timeoutMs,
  );
  const { port } = netsim.ports.listening;
  return { url: `ws://127.0.0.1:${port}/`, port, ...netsim };
}
