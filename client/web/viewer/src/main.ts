// The browser viewer: joins physics-server over WebSocket as a spectator or a player,
// draws every body as physics-view does (static grey, moving blue, still violet,
// kinematic teal, sensors a translucent green, the own body orange and ringed, moving
// bodies labelled), interpolated between snapshots by the playout buffer, steers the
// own body with the arrow keys and sends the game messages bound to keys. The last
// game messages received show in the panel. Query string (docs/WEB.md):
//   ?ws=ws://127.0.0.1:PORT/   the server's --ws-port (default ws://127.0.0.1:7778/)
//   &spectate=1                watch without a body
//   &name=N &token=T           Hello.client_name, Hello.access_token
//   &encoding=predicted|exact|full   the view's encoding (default predicted)
//   &keys=space:jump,x:shoot   keys that send game messages (a player's only)
// window.physicsViewer exposes what the page holds and drew, for tests and the console.
import { Client, ConnectionState, PlayoutBuffer, type BodyShape, type Encoding, type Snapshot } from "@physics/client";
import { type Camera, fit, toPixel } from "./camera";
import { GameLog, keyName, parseKeyMap } from "./game";
import * as palette from "./palette";

interface DrawnBody {
  id: string;
  x: number;
  y: number;
  kind: "dynamic" | "still" | "own" | "kinematic";
}

const params = new URLSearchParams(location.search);
const url = params.get("ws") ?? "ws://127.0.0.1:7778/";
const spectate = params.get("spectate") === "1";

const canvas = document.getElementById("view") as HTMLCanvasElement;
const context = canvas.getContext("2d")!;
const encoding = (params.get("encoding") ?? "predicted") as Encoding;
const client = new Client({
  url,
  spectate,
  name: params.get("name") ?? "web-viewer",
  token: params.get("token") ?? "",
  view: { encoding },
});
const shapes = new Map<bigint, BodyShape>();
let playout: PlayoutBuffer | undefined;
let camera: Camera | undefined;
let newest: Snapshot | undefined;
let previous: Snapshot | undefined;
let paused = false;
const keys = new Set<string>();
const rate = { bytes: 0, at: 0, kbitPerSecond: 0 };
const keyMap = parseKeyMap(params.get("keys"));
const game = new GameLog();
// Ids of the moving bodies added after the Welcome: players who joined since.
const joined = new Set<bigint>();

const api = {
  status: "connecting" as "connecting" | "connected" | "failed",
  error: "",
  url,
  spectator: spectate,
  bodyId: "",
  tickRate: 0,
  framesDrawn: 0,
  newestTick: -1,
  inSync: true,
  desyncs: 0,
  viewHashesChecked: 0,
  inputsSent: 0,
  camera: undefined as Camera | undefined,
  /** Game messages sent by the keys, received, and the last few received as text. */
  gameMessagesSent: 0,
  gameMessagesReceived: 0,
  gameMessages: [] as { tick: number; text: string }[],
  keyErrors: keyMap.errors,
  /** The panel's lines as last drawn. */
  panel: [] as string[],
  /** Every kinematic body as last drawn: id and position. */
  kinematic: [] as { id: string; x: number; y: number }[],
  /** Every sensor as last drawn: id and position. */
  sensors: [] as { id: string; x: number; y: number }[],
  /** The own body's position in the newest snapshot (a player's). */
  own: undefined as { x: number; y: number } | undefined,
  /** Stops drawing, draws the newest snapshot as decoded (not interpolated), and
   * returns what it drew: the tick, the camera and every moving body. */
  pause(): { tick: number; camera: Camera; bodies: DrawnBody[] } | undefined {
    paused = true;
    if (!newest || !camera) return undefined;
    const bodies = newestBodies(newest);
    draw(bodies);
    return { tick: newest.tick, camera, bodies };
  },
  resume(): void {
    if (!paused) return;
    paused = false;
    requestAnimationFrame(frame);
  },
};
(window as unknown as { physicsViewer: typeof api }).physicsViewer = api;

function kindOf(id: bigint, still: boolean): DrawnBody["kind"] {
  if (!client.welcome?.spectator && id === client.welcome?.bodyId) return "own";
  if (shapes.get(id)?.isKinematic) return "kinematic";
  return still ? "still" : "dynamic";
}

// The newest snapshot's bodies; still: the same state in the snapshot before it.
function newestBodies(snapshot: Snapshot): DrawnBody[] {
  const before = new Map((previous?.bodies ?? []).map((b) => [b.bodyId, b]));
  return snapshot.bodies.map((b) => {
    const p = before.get(b.bodyId);
    const still =
      p !== undefined &&
      p.position.x === b.position.x &&
      p.position.y === b.position.y &&
      p.velocity.x === b.velocity.x &&
      p.velocity.y === b.velocity.y;
    return { id: String(b.bodyId), x: b.position.x, y: b.position.y, kind: kindOf(b.bodyId, still) };
  });
}

function resize(): void {
  const width = Math.max(1, Math.round(canvas.clientWidth * devicePixelRatio));
  const height = Math.max(1, Math.round(canvas.clientHeight * devicePixelRatio));
  if (canvas.width !== width || canvas.height !== height || !camera) {
    canvas.width = width;
    canvas.height = height;
    if (client.welcome) camera = fit(client.welcome.bodies, width, height);
    api.camera = camera;
  }
}

function drawShape(shape: BodyShape, x: number, y: number, colour: palette.Rgb, alpha = 1): void {
  const cam = camera!;
  const [px, py] = toPixel(cam, x, y);
  context.fillStyle = palette.css(colour, alpha);
  if (shape.shape === "box") {
    const w = 2 * shape.halfExtents.x * cam.scale;
    const h = 2 * shape.halfExtents.y * cam.scale;
    context.fillRect(px - w / 2, py - h / 2, w, h);
    // The edge, one pixel inside, in the background's colour: stacked boxes read as boxes.
    if (w > 4 && h > 4 && alpha === 1) {
      context.strokeStyle = palette.css(palette.BACKGROUND);
      context.lineWidth = 1;
      context.strokeRect(px - w / 2 + 0.5, py - h / 2 + 0.5, w - 1, h - 1);
    }
  } else {
    context.beginPath();
    context.arc(px, py, Math.max(shape.radius * cam.scale, 1), 0, 2 * Math.PI);
    context.fill();
  }
}

function draw(bodies: DrawnBody[]): void {
  resize();
  context.fillStyle = palette.css(palette.BACKGROUND);
  context.fillRect(0, 0, canvas.width, canvas.height);
  if (!camera) return;
  for (const shape of shapes.values()) {
    if (shape.isStatic && !shape.isSensor) drawShape(shape, shape.position.x, shape.position.y, palette.STATIC);
  }
  // A kinematic body no snapshot carried is drawn where its shape was sent.
  const at = new Map<bigint, { x: number; y: number }>();
  for (const shape of shapes.values()) if (shape.isKinematic) at.set(shape.bodyId, shape.position);
  for (const body of bodies) at.set(BigInt(body.id), body);
  api.kinematic = [];
  for (const shape of shapes.values()) {
    const p = at.get(shape.bodyId);
    if (!shape.isKinematic || shape.isSensor || !p) continue;
    drawShape(shape, p.x, p.y, palette.KINEMATIC);
    api.kinematic.push({ id: String(shape.bodyId), x: p.x, y: p.y });
  }
  const colours = { dynamic: palette.DYNAMIC, still: palette.SLEEPING, own: palette.OWN, kinematic: palette.KINEMATIC };
  for (const body of bodies) {
    const shape = shapes.get(BigInt(body.id));
    if (shape && !shape.isStatic && !shape.isKinematic && !shape.isSensor) drawShape(shape, body.x, body.y, colours[body.kind]);
  }
  // Sensors over what is under them, translucent.
  api.sensors = [];
  for (const shape of shapes.values()) {
    const p = shape.isStatic ? shape.position : at.get(shape.bodyId);
    if (!shape.isSensor || !p) continue;
    drawShape(shape, p.x, p.y, palette.SENSOR, palette.SENSOR_ALPHA);
    api.sensors.push({ id: String(shape.bodyId), x: p.x, y: p.y });
  }
  drawMarks(bodies, at);
  drawPanel();
  api.framesDrawn += 1;
}

// A player's body's label: the own body's, and those of the moving bodies added since
// the Welcome (players who joined; the protocol does not say which of the Welcome's
// bodies are players'): the name, else the id; " (you)" on the own body.
function label(shape: BodyShape): string {
  const own = !client.welcome?.spectator && shape.bodyId === client.welcome?.bodyId;
  if (!own && (!joined.has(shape.bodyId) || shape.isSensor)) return "";
  const text = shape.name || `#${shape.bodyId}`;
  return own ? `${text} (you)` : text;
}

// The ring around the own body, and the labels above the moving bodies.
function drawMarks(bodies: DrawnBody[], at: Map<bigint, { x: number; y: number }>): void {
  const cam = camera!;
  const own = bodies.find((b) => b.kind === "own");
  const ownShape = own && shapes.get(BigInt(own.id));
  if (own && ownShape) {
    const [px, py] = toPixel(cam, own.x, own.y);
    context.strokeStyle = palette.css(palette.OWN_MARKER);
    context.lineWidth = 2;
    context.beginPath();
    if (ownShape.shape === "box") {
      const w = 2 * ownShape.halfExtents.x * cam.scale;
      const h = 2 * ownShape.halfExtents.y * cam.scale;
      context.rect(px - w / 2 - 3, py - h / 2 - 3, w + 6, h + 6);
    } else {
      context.arc(px, py, ownShape.radius * cam.scale + 3, 0, 2 * Math.PI);
    }
    context.stroke();
  }
  const size = Math.round(11 * devicePixelRatio);
  context.font = `${size}px monospace`;
  context.textAlign = "center";
  context.fillStyle = palette.css(palette.TEXT);
  for (const shape of shapes.values()) {
    const p = at.get(shape.bodyId);
    const text = p ? label(shape) : "";
    if (!p || !text) continue;
    const top = shape.shape === "box" ? shape.halfExtents.y : shape.radius;
    const [px, py] = toPixel(cam, p.x, p.y + top);
    context.fillText(text, px, py - 4);
  }
  context.textAlign = "start";
}

function drawPanel(): void {
  const welcome = client.welcome;
  const lines = [
    `${welcome?.sceneName || "scene"}  ${api.status}${spectate ? " (spectator)" : ""}`,
    `tick ${newest?.tick ?? "-"}  view hash ${api.inSync ? "in sync" : "DIFFERS"} (${api.viewHashesChecked} checked)`,
    `${rate.kbitPerSecond.toFixed(1)} kbit/s  ${newest?.bodies.length ?? 0} bodies`,
  ];
  if (!spectate) lines.push("arrow keys: steer");
  if (keyMap.map.size > 0) {
    const bound = [...keyMap.map].map(([k, p]) => `${k} ${new TextDecoder().decode(p)}`).join("  ");
    lines.push(spectate ? "game keys: a spectator sends none" : `game keys: ${bound}`);
  }
  for (const error of keyMap.errors) lines.push(`keys: ${error}`);
  if (game.sent > 0 || game.received > 0 || keyMap.map.size > 0) lines.push(...game.lines());
  if (api.error) lines.push(api.error);
  api.panel = lines;
  const size = Math.round(13 * devicePixelRatio);
  context.font = `${size}px monospace`;
  const width = Math.max(...lines.map((l) => context.measureText(l).width)) + size;
  context.fillStyle = "rgba(0, 0, 0, 0.67)";
  context.fillRect(0, 0, width, (lines.length + 0.6) * size * 1.3);
  context.fillStyle = palette.css(palette.TEXT);
  lines.forEach((line, i) => context.fillText(line, size / 2, (i + 1) * size * 1.3));
}

function frame(): void {
  if (paused) return;
  const now = performance.now();
  if (now - rate.at >= 1000) {
    rate.kbitPerSecond = rate.at === 0 ? 0 : ((client.stats.bytesReceived - rate.bytes) * 8) / (now - rate.at);
    rate.bytes = client.stats.bytesReceived;
    rate.at = now;
  }
  if (playout) {
    const state = playout.stateAt(performance.now() / 1000);
    draw(state.bodies.map((b) => ({ id: String(b.bodyId), x: b.position.x, y: b.position.y, kind: kindOf(b.bodyId, b.still) })));
  } else {
    draw([]);
  }
  requestAnimationFrame(frame);
}

// The arrow keys: an acceleration toward them, sent for the next tick when it changes.
function steer(): void {
  const welcome = client.welcome;
  if (!welcome || welcome.spectator || client.state !== ConnectionState.Connected) return;
  let dx = 0;
  let dy = 0;
  if (keys.has("ArrowLeft")) dx -= 1;
  if (keys.has("ArrowRight")) dx += 1;
  if (keys.has("ArrowDown")) dy -= 1;
  if (keys.has("ArrowUp")) dy += 1;
  const length = Math.hypot(dx, dy);
  const accel = Math.min(welcome.maxAcceleration, 30);
  const [ax, ay] = length > 0 ? [(dx / length) * accel, (dy / length) * accel] : [0, 0];
  // At a fixed rate an input for a tick already stepped applies at the next one.
  const tick = (newest?.tick ?? welcome.currentTick) + 1;
  if (client.sendInput(tick, ax, ay)) api.inputsSent += 1;
}

// A key of the map: its message, for the next tick (as an input for it would go).
function sendBound(event: KeyboardEvent): boolean {
  const payload = keyMap.map.get(keyName(event.key));
  if (!payload) return false;
  event.preventDefault();
  const welcome = client.welcome;
  if (event.repeat || !welcome || welcome.spectator || client.state !== ConnectionState.Connected) return true;
  const tick = (newest?.tick ?? welcome.currentTick) + 1;
  if (client.sendGameMessage(tick, payload)) {
    game.sent += 1;
    api.gameMessagesSent = game.sent;
  }
  return true;
}

function onKey(event: KeyboardEvent, down: boolean): void {
  if (down && sendBound(event)) return;
  if (!event.key.startsWith("Arrow")) return;
  event.preventDefault();
  const had = keys.has(event.key);
  if (down) keys.add(event.key);
  else keys.delete(event.key);
  if (had !== down) steer();
}
addEventListener("keydown", (e) => onKey(e, true));
addEventListener("keyup", (e) => onKey(e, false));
addEventListener("blur", () => {
  keys.clear();
  steer();
});

async function receive(): Promise<void> {
  for (;;) {
    const snapshot = await client.nextSnapshot(1000);
    if (!snapshot) {
      if (client.state !== ConnectionState.Connected) break;
      continue;
    }
    for (const shape of snapshot.added) {
      shapes.set(shape.bodyId, shape);
      if (!shape.isStatic) joined.add(shape.bodyId);
    }
    for (const id of snapshot.removed) {
      shapes.delete(id);
      joined.delete(id);
    }
    game.add(client.takeGameMessages());
    api.gameMessagesReceived = game.received;
    api.gameMessages = [...game.recent];
    playout!.push(snapshot, performance.now() / 1000);
    previous = newest;
    newest = snapshot;
    api.newestTick = snapshot.tick;
    const own = snapshot.bodies.find((b) => !client.welcome?.spectator && b.bodyId === client.welcome?.bodyId);
    if (own) api.own = { x: own.position.x, y: own.position.y };
    api.inSync = snapshot.inSync;
    api.desyncs = client.stats.desyncs;
    api.viewHashesChecked = client.stats.viewHashesChecked;
  }
  api.status = "failed";
  api.error = `${ConnectionState[client.state]}: ${client.lastError.detail}`;
}

async function main(): Promise<void> {
  requestAnimationFrame(frame);
  if (!(await client.connect(5000))) {
    api.status = "failed";
    api.error = `${ConnectionState[client.state]}: ${client.lastError.detail}`;
    return;
  }
  const welcome = client.welcome!;
  for (const shape of welcome.bodies) shapes.set(shape.bodyId, shape);
  playout = new PlayoutBuffer({ tickRate: welcome.tickRate, sendInterval: welcome.view.snapshotInterval / welcome.tickRate });
  camera = undefined;
  resize();
  api.status = "connected";
  api.bodyId = String(welcome.bodyId);
  api.tickRate = welcome.tickRate;
  await receive();
}

void main();
