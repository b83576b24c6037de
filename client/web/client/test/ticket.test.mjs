// Connect tickets minted in node (src/ticket.ts): the worked example of
// docs/PROTOCOL.md ("Connect tickets") to the byte, and a real physics-server started
// with --ticket-key-file admitting a node-minted ticket and refusing the others.
import { after, before, describe, test } from "node:test";
import assert from "node:assert/strict";
import { mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import WebSocket from "ws";
import { Client, ConnectionState } from "../dist/index.js";
import { mintTicket, ticketKeyFromHex, ticketKeyId } from "../dist/ticket.js";
import { protocolDoc } from "./doc.mjs";
import { startServer } from "./server.mjs";

const exampleKey = Uint8Array.from({ length: 32 }, (_, i) => i);
const exampleNonce = Uint8Array.from({ length: 16 }, (_, i) => 0xa0 + i);

function pageExample() {
  const bytes = protocolDoc.match(/The bytes are `([0-9a-f ]+)`/);
  const ticket = protocolDoc.match(/and the ticket is `([A-Za-z0-9_-]+)`/);
  if (!bytes || !ticket) throw new Error("no connect ticket worked example in docs/PROTOCOL.md");
  return { bytes: Buffer.from(bytes[1].replace(/ /g, ""), "hex"), ticket: ticket[1] };
}

test("the worked example of PROTOCOL.md, byte for byte", () => {
  const page = pageExample();
  const ticket = mintTicket({ playerId: 42n, seat: 1, room: "goal-rush", expiresAt: 1767225600n, nonce: exampleNonce }, exampleKey);
  assert.equal(ticket, page.ticket);
  assert.deepEqual(Buffer.from(ticket, "base64url"), page.bytes);
  assert.deepEqual(Buffer.from(ticketKeyId(exampleKey)), page.bytes.subarray(2, 6));
});

test("without a seat or a room: 100 characters, the seat flag clear, a fresh nonce each time", () => {
  const fields = { playerId: 7n, expiresAt: 2000000000n };
  const one = mintTicket(fields, exampleKey);
  const two = mintTicket(fields, exampleKey);
  assert.equal(one.length, 100);
  assert.notEqual(one, two);
  assert.equal(Buffer.from(one, "base64url")[1], 0);
});

test("a key is 64 hex digits; rooms over 64 bytes and bad seats are refused", () => {
  assert.deepEqual(ticketKeyFromHex("00".repeat(32) + "\n"), new Uint8Array(32));
  assert.throws(() => ticketKeyFromHex("00".repeat(31)));
  assert.throws(() => mintTicket({ playerId: 1n, expiresAt: 1n, room: "r".repeat(65) }, exampleKey));
  assert.throws(() => mintTicket({ playerId: 1n, expiresAt: 1n, seat: -1 }, exampleKey));
});

describe("physics-server --ticket-key-file and node-minted tickets", () => {
  const dir = mkdtempSync(join(tmpdir(), "ticket-test-"));
  const keyHex = "5a".repeat(32);
  const key = ticketKeyFromHex(keyHex);
  let server;
  before(async () => {
    writeFileSync(join(dir, "ticket.key"), keyHex + "\n", { mode: 0o600 });
    server = await startServer(["--ticket-key-file", join(dir, "ticket.key")]);
  });
  after(async () => {
    assert.equal(await server.stop(), 0);
    rmSync(dir, { recursive: true });
  });
  const inAnHour = () => BigInt(Math.floor(Date.now() / 1000) + 3600);

  test("a ticket minted here is welcomed; a second connection with it is refused while the first is in", async () => {
    const token = mintTicket({ playerId: 1234n, expiresAt: inAnHour() }, key);
    const first = new Client({ url: server.url, WebSocket, token });
    assert.ok(await first.connect(5000), first.lastError?.message);
    const second = new Client({ url: server.url, WebSocket, token });
    assert.equal(await second.connect(5000), false);
    assert.equal(second.state, ConnectionState.Refused);
    assert.equal(second.lastError.server.code, "BAD_TOKEN");
    assert.match(second.lastError.server.message, /connected already/);
    first.disconnect();
  });

  test("no ticket, another key's, an expired one: refused, each saying why", async () => {
    const refusals = [
      ["", /access_token is empty/],
      [mintTicket({ playerId: 5n, expiresAt: inAnHour() }, new Uint8Array(32)), /another key/],
      [mintTicket({ playerId: 5n, expiresAt: 1n }, key), /expired/],
    ];
    for (const [token, why] of refusals) {
      const c = new Client({ url: server.url, WebSocket, token });
      assert.equal(await c.connect(5000), false);
      assert.equal(c.lastError.server.code, "BAD_TOKEN");
      assert.match(c.lastError.server.message, why);
      assert.equal(c.welcome, undefined);
    }
  });
});
