// The viewer in headless Chromium against a real physics-server. What the page drew
// is checked against the server's bodies as a node client beside it decoded them
// (its view hash equal to the server's), pixel by pixel in a screenshot; and an
// arrow key held in the page moves the page's own body, as that client sees it.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import WebSocket from "ws";
import { Client, boxHalfSize } from "@physics/client";
import { startServer } from "../../client/test/server.mjs";
import { launch, openViewer, pixels } from "./viewer.mjs";

const BACKGROUND = [22, 24, 30];
const STATIC = [118, 124, 136];
const DYNAMIC = [70, 160, 255];
const STILL = [120, 90, 170];
const OWN = [255, 168, 40];
// The panel's corner, where text is drawn over the world.
const PANEL = { width: 360, height: 90 };

/** A node client that takes every snapshot as it comes, by tick. */
async function watcher(url, config = {}) {
  const client = new Client({ url, WebSocket, name: "beside", ...config });
  assert.ok(await client.connect(5000), client.lastError.detail);
  const byTick = new Map();
  let newest = 0;
  const running = (async () => {
    for (;;) {
      const s = await client.nextSnapshot(200);
      if (s) {
        byTick.set(s.tick, s);
        newest = s.tick;
      } else if (client.state !== 3) return;
    }
  })();
  return {
    client,
    byTick,
    newest: () => newest,
    async until(predicate, what, timeoutMs = 10000) {
      const deadline = Date.now() + timeoutMs;
      while (!predicate()) {
        assert.ok(Date.now() < deadline, `timed out waiting for ${what}`);
        await new Promise((resolve) => setTimeout(resolve, 20));
      }
    },
    async stop() {
      client.disconnect();
      await running;
    },
  };
}

/** physics-view's camera, computed here from the Welcome's bodies. */
function fit(bodies, width, height) {
  let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const b of bodies) {
    const h = boxHalfSize(b);
    minX = Math.min(minX, b.position.x - h.x);
    maxX = Math.max(maxX, b.position.x + h.x);
    minY = Math.min(minY, b.position.y - h.y);
    maxY = Math.max(maxY, b.position.y + h.y);
  }
  const scale = Math.min(width / ((maxX - minX) * 1.05), height / ((maxY - minY) * 1.05));
  const cx = (minX + maxX) / 2;
  const cy = (minY + maxY) / 2;
  return { scale, toPixel: (x, y) => [Math.floor(width / 2 + (x - cx) * scale), Math.floor(height / 2 - (y - cy) * scale)] };
}

function underPanel([px, py]) {
  return px < PANEL.width && py < PANEL.height;
}

describe("the viewer", () => {
  let browser;
  before(async () => {
    browser = await launch();
  });
  after(async () => browser?.close());

  test("a spectator draws the server's bodies where the server has them", async (t) => {
    // Lockstep: the world steps only while the player below sends inputs, so that
    // it stands still for the screenshot.
    const server = await startServer(["--lockstep", "--lockstep-pace", "asap"]);
    const beside = await watcher(server.url, { spectate: true });
    const { page, errors } = await openViewer(browser, server.url, "&spectate=1");
    try {
      await page.waitForFunction(() => window.physicsViewer?.status === "connected", { timeout: 10000 });
      const player = new Client({ url: server.url, WebSocket, name: "stepper" });
      assert.ok(await player.connect(5000));
      let tick = player.welcome.currentTick;
      // One tick at a time, each once the page has it: a spectator whose window is
      // full skips ticks, and a frozen world would never send it the last one.
      for (let n = 0; n < 120; ++n) {
        player.sendInput(tick + 1, 0, 0);
        tick = (await player.nextSnapshot(5000)).tick;
        await page.waitForFunction((t) => window.physicsViewer.newestTick === t, { timeout: 10000 }, tick);
      }
      const last = tick;
      await beside.until(() => beside.byTick.has(last) && beside.byTick.has(last - 1), `tick ${last} beside`);
      await page.waitForFunction((t) => window.physicsViewer.newestTick === t, { timeout: 10000 }, last);

      const drawn = await page.evaluate(() => window.physicsViewer.pause());
      const state = await page.evaluate(() => ({ ...window.physicsViewer }));
      assert.equal(drawn.tick, last);
      assert.equal(state.inSync, true);
      assert.equal(state.desyncs, 0);
      assert.ok(state.viewHashesChecked > 0, "the page compared no view hash");

      // What the page decoded equals what the node client decoded, bit for bit.
      const truth = beside.byTick.get(last);
      assert.equal(beside.client.stats.desyncs, 0);
      assert.deepEqual(
        drawn.bodies.map((b) => [b.id, b.x, b.y]),
        truth.bodies.map((b) => [String(b.bodyId), b.position.x, b.position.y]),
      );

      const shot = pixels(await page.screenshot());
      assert.equal(shot.width, 960);
      const welcome = beside.client.welcome;
      const camera = fit(welcome.bodies, shot.width, shot.height);
      assert.ok(Math.abs(camera.scale - drawn.camera.scale) < 1e-9, "the page's camera is physics-view's");
      const shapes = new Map(welcome.bodies.map((b) => [b.bodyId, b]));
      for (const s of beside.byTick.values()) for (const b of s.added) shapes.set(b.bodyId, b);
      const before = new Map(beside.byTick.get(last - 1).bodies.map((b) => [b.bodyId, b]));
      // Every body's footprint in pixels, to leave out centres another body covers.
      const footprints = [];
      for (const shape of shapes.values()) {
        const at = shape.isStatic ? shape.position : truth.bodies.find((b) => b.bodyId === shape.bodyId)?.position;
        if (!at) continue;
        const h = boxHalfSize(shape);
        footprints.push({ id: shape.bodyId, min: camera.toPixel(at.x - h.x, at.y + h.y), max: camera.toPixel(at.x + h.x, at.y - h.y) });
      }
      const covered = ([px, py], id, margin = 0) =>
        footprints.some((f) => f.id !== id && px >= f.min[0] - margin && px <= f.max[0] + margin && py >= f.min[1] - margin && py <= f.max[1] + margin);

      let checked = 0;
      for (const body of truth.bodies) {
        const shape = shapes.get(body.bodyId);
        const pixel = camera.toPixel(body.position.x, body.position.y);
        if (underPanel(pixel) || covered(pixel, body.bodyId) || boxHalfSize(shape).x * camera.scale < 2) continue;
        const p = before.get(body.bodyId);
        const still = p && p.position.x === body.position.x && p.position.y === body.position.y && p.velocity.x === body.velocity.x && p.velocity.y === body.velocity.y;
        assert.deepEqual(shot.at(...pixel), still ? STILL : DYNAMIC, `body ${body.bodyId} at pixel ${pixel}`);
        ++checked;
      }
      assert.ok(checked >= 4, `only ${checked} moving bodies could be checked`);
      let statics = 0;
      for (const shape of welcome.bodies.filter((b) => b.isStatic)) {
        const pixel = camera.toPixel(shape.position.x, shape.position.y);
        if (underPanel(pixel) || covered(pixel, shape.bodyId)) continue;
        assert.deepEqual(shot.at(...pixel), STATIC, `static body ${shape.bodyId} at pixel ${pixel}`);
        ++statics;
      }
      assert.ok(statics >= 3, `only ${statics} static bodies could be checked`);
      // Away from every body and the panel: the background.
      let empty = 0;
      for (let py = 5; py < shot.height; py += 37) {
        for (let px = 5; px < shot.width; px += 41) {
          if (underPanel([px, py]) || covered([px, py], undefined, 3)) continue;
          assert.deepEqual(shot.at(px, py), BACKGROUND, `pixel ${px}, ${py}`);
          ++empty;
        }
      }
      assert.ok(empty > 100);
      t.diagnostic(`tick ${last}: ${checked} moving bodies, ${statics} static bodies, ${empty} background pixels checked`);
      assert.deepEqual(errors, []);
      player.disconnect();
    } finally {
      await page.close();
      await beside.stop();
      assert.equal(await server.stop(), 0);
    }
  });

  test("a player: an arrow key held moves the own body, drawn orange", async () => {
    const server = await startServer([]);
    const beside = await watcher(server.url, { spectate: true });
    const { page, errors } = await openViewer(browser, server.url);
    try {
      await page.waitForFunction(() => window.physicsViewer?.status === "connected", { timeout: 10000 });
      const state = await page.evaluate(() => ({ ...window.physicsViewer }));
      assert.equal(state.spectator, false);
      const id = BigInt(state.bodyId);
      assert.notEqual(id, 0n);
      const own = () => beside.byTick.get(beside.newest())?.bodies.find((b) => b.bodyId === id);
      await beside.until(() => own() !== undefined, "the page's body beside");
      const xs = beside.client.welcome.bodies.map((b) => b.position.x);
      const centerX = (Math.min(...xs) + Math.max(...xs)) / 2;
      const x0 = own().position.x;
      const key = x0 < centerX ? "ArrowRight" : "ArrowLeft";
      const sign = key === "ArrowRight" ? 1 : -1;
      await page.keyboard.down(key);
      await beside.until(() => sign * (own().position.x - x0) > 1, `the body to move 1 m with ${key} (from ${x0})`);
      await page.keyboard.up(key);
      const after = await page.evaluate(() => ({ ...window.physicsViewer }));
      assert.ok(after.inputsSent >= 2, `${after.inputsSent} inputs sent`);

      // Drawn orange where the page holds it.
      const drawn = await page.evaluate(() => window.physicsViewer.pause());
      const mine = drawn.bodies.find((b) => b.id === state.bodyId);
      assert.equal(mine.kind, "own");
      const camera = fit(beside.client.welcome.bodies, 960, 600);
      const shot = pixels(await page.screenshot());
      assert.deepEqual(shot.at(...camera.toPixel(mine.x, mine.y)), OWN);
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
      await beside.stop();
      assert.equal(await server.stop(), 0);
    }
  });
});
