// ServerError.code names every physics.wire.ErrorCode of proto/wire.proto by its name
// without the ERROR_ prefix, and a code newer than the client by its number
// (tests/proto/error_codes_test.py ties the C++ client's enum the same way).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { create } from "@bufbuild/protobuf";
import { wire } from "../dist/index.js";
import { errorFromWire } from "../dist/convert.js";

const proto = readFileSync(new URL("../../../../proto/wire.proto", import.meta.url), "utf8");
const body = proto.slice(proto.indexOf("enum ErrorCode {"));
const codes = [...body.slice(0, body.indexOf("}")).matchAll(/^\s*ERROR_([A-Z0-9_]+)\s*=\s*(\d+)\s*;/gm)]
  .map(([, name, number]) => ({ name, number: Number(number) }));

test("every ErrorCode of wire.proto reaches ServerError.code by its name", () => {
  assert.ok(codes.length >= 20, `read ${codes.length} codes from wire.proto`);
  for (const { name, number } of codes) {
    const error = errorFromWire(create(wire.ErrorSchema, { code: number, message: "m", fatal: true }));
    assert.equal(error.code, name, `code ${number}`);
    assert.equal(error.rawCode, number);
  }
});

test("a code newer than the client is given by its number", () => {
  const newest = Math.max(...codes.map((c) => c.number));
  const error = errorFromWire(create(wire.ErrorSchema, { code: newest + 1 }));
  assert.equal(error.code, String(newest + 1));
  assert.equal(error.rawCode, newest + 1);
});
