// physics-server as a child process for the tests: its WebSocket port read from the
// "websocket on ADDRESS:PORT" line it prints once it listens. The binary is
// $PHYSICS_SERVER, or build/server/physics-server under the repository's root.
import { spawn } from "node:child_process";
import { existsSync } from "node:fs";
import { createInterface } from "node:readline";
import { repoRoot } from "./doc.mjs";

export const serverBinary = process.env.PHYSICS_SERVER || `${repoRoot}build/server/physics-server`;

/** Starts physics-server with `args` (plus --port 0 --ws-port 0); resolves to
 * { url, port, wsPort, stop(), log() } once it has printed both ports. */
export async function startServer(args = [], { timeoutMs = 10000 } = {}) {
  if (!existsSync(serverBinary)) {
    throw new Error(`no physics-server at ${serverBinary}: build it, or set PHYSICS_SERVER`);
  }
  const child = spawn(serverBinary, ["--port", "0", "--ws-port", "0", "--stats-interval-s", "0", ...args], {
    stdio: ["ignore", "pipe", "pipe"],
  });
  let stderr = "";
  child.stderr.on("data", (chunk) => {
    stderr += chunk;
  });
  const exited = new Promise((resolve) => child.on("exit", (code, signal) => resolve({ code, signal })));
  const lines = createInterface({ input: child.stdout });
  const ports = {};
  await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`physics-server printed no ports in ${timeoutMs} ms:\n${stderr}`)), timeoutMs);
    exited.then(({ code, signal }) => reject(new Error(`physics-server exited (${code ?? signal}) before listening:\n${stderr}`)));
    lines.on("line", (line) => {
      // An IPv6 address is printed bare: the port follows the last colon.
      const match = line.match(/^(listening|websocket) on (.*):(\d+)$/);
      if (!match) return;
      ports[match[1]] = { host: match[2], port: Number(match[3]) };
      if (ports.listening && ports.websocket) {
        clearTimeout(timer);
        resolve();
      }
    });
  });
  const host = ports.websocket.host.includes(":") ? `[${ports.websocket.host}]` : ports.websocket.host;
  return {
    url: `ws://${host}:${ports.websocket.port}/`,
    port: ports.listening.port,
    wsPort: ports.websocket.port,
    log: () => stderr,
    /** SIGTERM; resolves to the exit code (0: a clean shutdown). */
    async stop() {
      if (child.exitCode === null && child.signalCode === null) child.kill("SIGTERM");
      const { code } = await exited;
      return code;
    },
  };
}

export const netsimBinary = process.env.PHYSICS_NETSIM || `${repoRoot}build/testing/physics-netsim`;

/** Starts physics-netsim relaying to the server's port `targetPort` with `args` (its
 * path: --latency-ms and so on); resolves to { url, port, stop() } once it listens. */
export async function startNetsim(targetPort, args = [], { timeoutMs = 10000 } = {}) {
  if (!existsSync(netsimBinary)) {
    throw new Error(`no physics-netsim at ${netsimBinary}: build it, or set PHYSICS_NETSIM`);
  }
  const child = spawn(netsimBinary, ["--port", "0", "--to", `127.0.0.1:${targetPort}`, ...args], {
    stdio: ["ignore", "pipe", "pipe"],
  });
  let stderr = "";
  child.stderr.on("data", (chunk) => {
    stderr += chunk;
  });
  const exited = new Promise((resolve) => child.on("exit", (code, signal) => resolve({ code, signal })));
  const lines = createInterface({ input: child.stdout });
  const port = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`physics-netsim printed no port in ${timeoutMs} ms:\n${stderr}`)), timeoutMs);
    exited.then(({ code, signal }) => reject(new Error(`physics-netsim exited (${code ?? signal}):\n${stderr}`)));
    lines.on("line", (line) => {
      const match = line.match(/^listening on (.*):(\d+)$/);
      if (!match) return;
      clearTimeout(timer);
      resolve(Number(match[2]));
    });
  });
  return {
    url: `ws://127.0.0.1:${port}/`,
    port,
    async stop() {
      if (child.exitCode === null && child.signalCode === null) child.kill("SIGTERM");
      await exited;
    },
  };
}
