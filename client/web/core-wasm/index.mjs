// The physics core in WebAssembly: a world from a flat world (an array of numbers,
// as `physics-flatten SCENE.textproto` writes it; portable/flat_world.h gives the
// layout), steps, the bodies, inputs and the state hash, equal bit for bit to the
// server's and physics-sim's on the same scene.
//
//   import { loadCore } from '@physics/core-wasm';
//   const core = await loadCore();
//   const world = core.createWorld(JSON.parse(text));
//   world.step(600);
//   world.stateHash();   // '1f0c...', as `physics-sim --scene S --steps 600` prints it
//   world.free();
//
// The module is dist/physics-core.js and dist/physics-core.wasm, which
// scripts/test-wasm.sh builds with Debian's emscripten. Under node 20, run with
// --no-experimental-fetch (that emscripten's loader otherwise fetches the .wasm).
import createPhysicsCore from './dist/physics-core.js';

const kBodyFields = 8;

export class World {
  #core;
  #handle;

  constructor(core, handle) {
    this.#core = core;
    this.#handle = handle;
  }

  // The scene's fixed step in seconds (1 / tick rate).
  get dt() {
    return this.#core._pc_dt(this.#handle);
  }

  // `steps` fixed steps of dt.
  step(steps = 1) {
    if (!Number.isInteger(steps) || steps < 0 || steps > 0xffffffff) {
      throw new RangeError(`steps must be a whole number in [0, 2^32), got ${steps}`);
    }
    this.#core._pc_step(this.#handle, steps);
  }

  get bodyCount() {
    return this.#core._pc_body_count(this.#handle);
  }

  // Every body, in id order: { index, shape: 'circle'|'box', x, y, vx, vy, awake, dynamic }.
  bodies() {
    const core = this.#core;
    const count = core._pc_body_count(this.#handle);
    const bytes = Math.max(1, count) * kBodyFields * 8;
    const pointer = core._malloc(bytes);
    try {
      const written = core._pc_read_bodies(this.#handle, pointer, count);
      const rows = core.HEAPF64.subarray(pointer / 8, pointer / 8 + written * kBodyFields);
      const out = [];
      for (let i = 0; i < written; ++i) {
        const r = rows.subarray(i * kBodyFields, (i + 1) * kBodyFields);
        out.push({
          index: r[0],
          shape: r[1] === 0 ? 'circle' : 'box',
          x: r[2],
          y: r[3],
          vx: r[4],
          vy: r[5],
          awake: r[6] === 1,
          dynamic: r[7] === 1,
        });
      }
      return out;
    } finally {
      core._free(pointer);
    }
  }

  // A client's input: body `index` (its place in the flat world) accelerates by
  // (ax, ay) m/s^2 until set again. False for an unknown index, a static body or a
  // non-finite value.
  setAcceleration(index, ax, ay) {
    if (!Number.isInteger(index) || index < 0 || index > 0xffffffff) return false;
    return this.#core._pc_set_acceleration(this.#handle, index, ax, ay) === 1;
  }

  // World::state_hash as 16 hex digits.
  stateHash() {
    return this.#core.UTF8ToString(this.#core._pc_state_hash(this.#handle));
  }

  free() {
    if (this.#handle !== 0) this.#core._pc_destroy(this.#handle);
    this.#handle = 0;
  }
}

export async function loadCore(options = {}) {
  const core = await createPhysicsCore(options);
  return {
    // A world from a flat world's numbers (an array or a Float64Array). Throws an
    // Error saying which value is wrong when they do not describe a world.
    createWorld(values) {
      if (!Array.isArray(values) && !(values instanceof Float64Array)) {
        throw new TypeError('a flat world is an array of numbers');
      }
      const numbers = Float64Array.from(values, Number);
      const pointer = core._malloc(Math.max(1, numbers.length) * 8);
      try {
        core.HEAPF64.set(numbers, pointer / 8);
        const handle = core._pc_create(pointer, numbers.length);
        if (handle === 0) throw new Error(core.UTF8ToString(core._pc_last_error()));
        return new World(core, handle);
      } finally {
        core._free(pointer);
      }
    },
  };
}
