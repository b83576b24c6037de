// The WebAssembly core against the native one: every scene stepped here ends on the
// hash native physics-sim printed for it. scripts/test-wasm.sh writes the cases
// (CORE_WASM_CASES: a JSON array of { scene, flat, steps, hash }, flat being
// physics-flatten's output) and runs this with node's test runner.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore } from '../index.mjs';

const casesFile = process.env.CORE_WASM_CASES;
const cases = casesFile ? JSON.parse(readFileSync(casesFile, 'utf8')) : [];
const core = await loadCore();
const flatOf = (c) => JSON.parse(readFileSync(c.flat, 'utf8'));

test('the cases are there (CORE_WASM_CASES, written by scripts/test-wasm.sh)', () => {
  assert.ok(casesFile, 'CORE_WASM_CASES is not set');
  assert.ok(cases.length > 0, 'no cases');
});

for (const c of cases) {
  test(`${c.scene}: ${c.steps} steps end on native physics-sim's hash`, () => {
    const world = core.createWorld(flatOf(c));
    world.step(c.steps);
    assert.equal(world.stateHash(), c.hash);
    world.free();
  });
}

test('bodies are read in id order and move', () => {
  const c = cases[0];
  const world = core.createWorld(flatOf(c));
  const before = world.bodies();
  assert.equal(before.length, world.bodyCount);
  assert.deepEqual(before.map((b) => b.index), [...before.keys()]);
  world.step(60);
  const after = world.bodies();
  const moved = after.filter((b, i) => b.dynamic && (b.x !== before[i].x || b.y !== before[i].y));
  assert.ok(moved.length > 0, 'no dynamic body moved in a second');
  assert.ok(after.filter((b) => !b.dynamic).every((b, i) => b.vx === 0 && b.vy === 0 && i >= 0));
  world.free();
});

test('an input changes the world, as it does natively', () => {
  const c = cases[0];
  const plain = core.createWorld(flatOf(c));
  const pushed = core.createWorld(flatOf(c));
  const dynamicIndex = pushed.bodies().find((b) => b.dynamic).index;
  assert.equal(pushed.setAcceleration(dynamicIndex, 5, 0), true);
  assert.equal(pushed.setAcceleration(1e9, 5, 0), false);
  assert.equal(pushed.setAcceleration(dynamicIndex, NaN, 0), false);
  plain.step(30);
  pushed.step(30);
  assert.notEqual(pushed.stateHash(), plain.stateHash());
  plain.free();
  pushed.free();
});

test('numbers that are not a world are refused with the reason', () => {
  const flat = flatOf(cases[0]);
  assert.throws(() => core.createWorld([]), /version/);
  assert.throws(() => core.createWorld([2, ...flat.slice(1)]), /version/);
  assert.throws(() => core.createWorld(flat.slice(0, 20)), /at least 28 values/);
  assert.throws(() => core.createWorld(flat.slice(0, flat.length - 1)), /bodies take/);
  const badIntegrator = [...flat];
  badIntegrator[3] = 7;
  assert.throws(() => core.createWorld(badIntegrator), /integrator/);
  const badRadius = [...flat];
  badRadius.splice(28, 16, 0, 1, 0, 0, 0, 0, 0, 0, -1, 0.5, 0.5, 1, 0, 0, 0, 0);
  assert.throws(() => core.createWorld(badRadius), /body 0 refused by the world/);
  assert.throws(() => core.createWorld('[1]'), TypeError);
  const world = core.createWorld(flat);
  assert.throws(() => world.step(-1), RangeError);
  world.free();
});
