// The test vectors the C++ and the TypeScript clients share (tests/vectors/*.json): one
// file per twin, inputs and expected outputs, read by both languages' tests.
import { readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import assert from "node:assert/strict";

const dir = fileURLToPath(new URL("../../../../tests/vectors/", import.meta.url));

export function loadVectors(name) {
  return JSON.parse(readFileSync(`${dir}${name}.json`, "utf8"));
}

// JSON has no NaN or infinity: the files write them as strings.
export function num(value) {
  if (value === "nan") return NaN;
  if (value === "inf") return Infinity;
  if (value === "-inf") return -Infinity;
  return value;
}

// snake_case (the files' names, as C++ spells them) to camelCase (TypeScript's).
export function camel(name) {
  return name.replace(/_([a-z])/g, (_, letter) => letter.toUpperCase());
}

export function camelKeys(object) {
  return Object.fromEntries(Object.entries(object ?? {}).map(([key, value]) => [camel(key), value]));
}

export function near(actual, expected, tolerance, what) {
  assert.ok(Math.abs(actual - expected) <= tolerance, `${what}: ${actual}, expected ${expected} ± ${tolerance}`);
}
