// The viewer in a game, in headless Chromium against a real physics-server with
// rules: a key of the `keys` map sends its game message and the rules' answer shows
// in the panel; on goal rush, space makes the own body jump, and the goals (sensors) are drawn translucent over
// what is under them, the platform (kinematic) in its own colour, and its pixels move
// between two screenshots.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import { existsSync, writeFileSync } from "node:fs";
import { startServer } from "../../client/test/server.mjs";
import { launch, openViewer, pixels, repoRoot } from "./viewer.mjs";

const BACKGROUND = [22, 24, 30];
const KINEMATIC = [60, 200, 170];
const SENSOR = [120, 230, 110];
const SENSOR_ALPHA = 80 / 255;
// Rules that answer every message "got <payload>" (tests/client/echo_rules_plugin.cpp),
// and goal rush's (examples/goal-rush), as libraries physics-server loads.
const echoRules = process.env.PHYSICS_ECHO_RULES || `${repoRoot}build/tests/client/libphysics_test_rules_echo.so`;
const goalRushRules = process.env.PHYSICS_GOAL_RUSH_RULES || `${repoRoot}build/examples/goal-rush/libgoal_rush.so`;
const goalRushScene = `${repoRoot}examples/goal-rush/goal-rush.textproto`;

function need(path) {
  assert.ok(existsSync(path), `no ${path}: build it (scripts/test-web.sh does)`);
}

/** A colour at `alpha` over `under`; the canvas blends in 8 bits, a unit or two off. */
function assertBlend(found, top, under, what) {
  for (let i = 0; i < 3; ++i) {
    const want = top[i] * SENSOR_ALPHA + under[i] * (1 - SENSOR_ALPHA);
    assert.ok(Math.abs(found[i] - want) <= 2, `${what}: found ${found}, want about ${top} at ${SENSOR_ALPHA.toFixed(3)} over ${under}`);
  }
}

function toPixel(camera, x, y) {
  return [Math.floor(camera.width / 2 + (x - camera.centerX) * camera.scale), Math.floor(camera.height / 2 - (y - camera.centerY) * camera.scale)];
}

describe("the viewer in a game", () => {
  let browser;
  before(async () => {
    browser = await launch();
  });
  after(async () => browser?.close());

  test("a key of the map sends its game message; the rules' answer shows in the panel", async () => {
    need(echoRules);
    const server = await startServer(["--rules", echoRules]);
    const { page, errors } = await openViewer(browser, server.url, "&keys=space:jump,x:shoot,ctrl:nothing");
    try {
      await page.waitForFunction(() => window.physicsViewer?.status === "connected" && window.physicsViewer.newestTick > 0, { timeout: 10000 });
      const before = await page.evaluate(() => ({ ...window.physicsViewer }));
      assert.deepEqual(before.keyErrors, ["unknown key 'ctrl'"]);
      assert.equal(before.gameMessagesSent, 0);
      assert.equal(before.gameMessagesReceived, 0);

      await page.keyboard.press("Space");
      await page.waitForFunction(() => window.physicsViewer.gameMessagesReceived >= 1, { timeout: 10000 });
      await page.keyboard.press("x");
      await page.waitForFunction(() => window.physicsViewer.gameMessagesReceived >= 2, { timeout: 10000 });
      // A key of no binding sends nothing.
      await page.keyboard.press("y");
      await page.waitForFunction(() => window.physicsViewer.panel.some((l) => l.includes("got shoot")), { timeout: 10000 });
      const state = await page.evaluate(() => ({ ...window.physicsViewer }));
      assert.equal(state.gameMessagesSent, 2);
      assert.equal(state.gameMessagesReceived, 2);
      assert.deepEqual(
        state.gameMessages.map((m) => m.text),
        ["got jump", "got shoot"],
      );
      assert.ok(state.gameMessages[0].tick > 0 && state.gameMessages[1].tick >= state.gameMessages[0].tick);
      assert.ok(state.panel.some((l) => l.includes("game keys: space jump  x shoot")), state.panel.join("\n"));
      assert.ok(state.panel.some((l) => l === `  tick ${state.gameMessages[0].tick}: got jump`), state.panel.join("\n"));
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
      assert.equal(await server.stop(), 0);
    }
  });

  test("goal rush: space jumps; the goals translucent, the platform in its colour, moving between two screenshots", async (t) => {
    need(goalRushRules);
    const server = await startServer(["--rules", goalRushRules, "--scene", goalRushScene]);
    const { page, errors } = await openViewer(browser, server.url, "&encoding=exact&keys=space:jump");
    try {
      await page.waitForFunction(() => window.physicsViewer?.status === "connected" && window.physicsViewer.own, { timeout: 10000 });
      // Goal rush's rules take "jump" from a player on the ground: pressed until the
      // own body rises half a metre above where it stood.
      const y0 = await page.evaluate(() => window.physicsViewer.own.y);
      let risen = false;
      for (let tries = 0; tries < 50 && !risen; ++tries) {
        await page.keyboard.press("Space");
        risen = await page
          .waitForFunction((y) => window.physicsViewer.own.y > y + 0.5, { timeout: 300 }, y0)
          .then(() => true, () => false);
      }
      assert.ok(risen, "the own body did not jump");
      assert.ok((await page.evaluate(() => window.physicsViewer.gameMessagesSent)) >= 1);
      const first = await page.evaluate(() => window.physicsViewer.pause());
      const shot1 = pixels(await page.screenshot());
      const kinematic1 = await page.evaluate(() => window.physicsViewer.kinematic);
      assert.equal(kinematic1.length, 1, "goal rush has one kinematic body, the platform");
      const platform = kinematic1[0];
      const camera = first.camera;

      // The platform's centre, in its colour.
      assert.deepEqual(shot1.at(...toPixel(camera, platform.x, platform.y)), KINEMATIC);
      // The goals: static sensors, translucent over the background (their middle,
      // where no body is at the start).
      const goals = await page.evaluate(() => window.physicsViewer.sensors);
      assert.equal(goals.length, 2, "goal rush has two sensors, the goals");
      for (const goal of goals) {
        assertBlend(shot1.at(...toPixel(camera, goal.x, goal.y)), SENSOR, BACKGROUND, `goal ${goal.id}`);
      }

      const carried = first.bodies.some((b) => b.id === platform.id);
      if (!carried) {
        t.skip("waits for kinematic bodies in the snapshots: the platform is drawn where its shape was sent");
        return;
      }
      // Later: the rules move the platform along its path.
      await page.evaluate(() => window.physicsViewer.resume());
      await page.waitForFunction((tick) => window.physicsViewer.newestTick >= tick + 30, { timeout: 10000 }, first.tick);
      const second = await page.evaluate(() => window.physicsViewer.pause());
      const png2 = await page.screenshot();
      // docs/images/web-viewer.png is this picture (docs/WEB.md).
      if (process.env.WEB_VIEWER_GAME_SCREENSHOT) writeFileSync(process.env.WEB_VIEWER_GAME_SCREENSHOT, png2);
      const shot2 = pixels(png2);
      const moved = second.bodies.find((b) => b.id === platform.id);
      assert.ok(moved, "the platform in the second snapshot");
      const [x1, y1] = toPixel(camera, platform.x, platform.y);
      const [x2, y2] = toPixel(camera, moved.x, moved.y);
      assert.ok(Math.hypot(x2 - x1, y2 - y1) >= 3, `the platform moved ${x2 - x1}, ${y2 - y1} px`);
      assert.deepEqual(shot2.at(x2, y2), KINEMATIC);
      // Its pixels moved with it: the row through its centre, in both pictures, holds
      // the platform's colour over spans that are shifted by its move.
      const span = (shot, y) => {
        const xs = [];
        for (let x = 0; x < shot.width; ++x) if (shot.at(x, y).every((c, i) => c === KINEMATIC[i])) xs.push(x);
        return [Math.min(...xs), Math.max(...xs)];
      };
      const [a1, b1] = span(shot1, y1);
      const [a2, b2] = span(shot2, y2);
      assert.ok(Math.abs(a2 - a1 - (x2 - x1)) <= 1 && Math.abs(b2 - b1 - (x2 - x1)) <= 1, `spans ${a1}-${b1} then ${a2}-${b2}, moved ${x2 - x1} px`);
      assert.deepEqual(errors, []);
    } finally {
      await page.close();
      assert.equal(await server.stop(), 0);
    }
  });
});
