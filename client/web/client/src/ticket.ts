// Connect tickets for physics-server --ticket-key-file (docs/PROTOCOL.md, "Connect
// tickets"), minted by a game's backend in node: the same bytes as physics-ticket and
// the server's own code, sealed with HMAC-SHA-256 from node:crypto. Imported as
// "@physics/client/ticket", apart from the client: a ticket is minted where the key
// is, on the backend, never in a player's browser.
import { createHmac, randomBytes } from "node:crypto";

export const TICKET_VERSION = 1;
export const TICKET_KEY_BYTES = 32;
export const TICKET_NONCE_BYTES = 16;
export const TICKET_MAX_ROOM_BYTES = 64;

const KEY_ID_LABEL = "physics ticket key id";
const HAS_SEAT = 0x01;

export interface TicketFields {
  /** Your backend's id for the player: one connection per id at a time. */
  playerId: bigint;
  /** The seat held for the player in a lockstep lobby; none: the lowest free one. */
  seat?: number;
  /** The room (the server's scene name, or --ticket-room) it is for; none: any room. */
  room?: string;
  /** Unix seconds; the ticket is valid while the server's clock is before it. */
  expiresAt: bigint;
  /** 16 bytes; random when not given (tests give one to get fixed bytes). */
  nonce?: Uint8Array;
}

/** A key file's first line (64 hexadecimal digits, physics-ticket --new-key) as the key. */
export function ticketKeyFromHex(hex: string): Uint8Array {
  const text = hex.trim();
  if (!/^[0-9a-fA-F]{64}$/.test(text)) throw new Error("a ticket key is 64 hexadecimal digits");
  return Uint8Array.from(Buffer.from(text, "hex"));
}

/** The first 4 bytes of HMAC-SHA-256(key, "physics ticket key id"): tells keys apart. */
export function ticketKeyId(key: Uint8Array): Uint8Array {
  return Uint8Array.from(createHmac("sha256", key).update(KEY_ID_LABEL).digest().subarray(0, 4));
}

/** The ticket's text (base64url, no padding), for Hello.access_token (ClientConfig.token). */
export function mintTicket(fields: TicketFields, key: Uint8Array): string {
  if (key.length !== TICKET_KEY_BYTES) throw new Error(`a ticket key is ${TICKET_KEY_BYTES} bytes`);
  const room = Buffer.from(fields.room ?? "", "utf8");
  if (room.length > TICKET_MAX_ROOM_BYTES) throw new Error(`a ticket's room is at most ${TICKET_MAX_ROOM_BYTES} bytes`);
  const nonce = fields.nonce ?? randomBytes(TICKET_NONCE_BYTES);
  if (nonce.length !== TICKET_NONCE_BYTES) throw new Error(`a ticket's nonce is ${TICKET_NONCE_BYTES} bytes`);
  const seat = fields.seat;
  if (seat !== undefined && !(Number.isInteger(seat) && seat >= 0 && seat <= 0xffffffff)) {
    throw new Error("a seat is a 32-bit unsigned integer");
  }
  const body = Buffer.alloc(43 + room.length);
  body.writeUInt8(TICKET_VERSION, 0);
  body.writeUInt8(seat !== undefined ? HAS_SEAT : 0, 1);
  body.set(ticketKeyId(key), 2);
  body.writeBigUInt64LE(BigInt.asUintN(64, fields.playerId), 6);
  body.writeUInt32LE(seat ?? 0, 14);
  body.writeBigUInt64LE(BigInt.asUintN(64, fields.expiresAt), 18);
  body.set(nonce, 26);
  body.writeUInt8(room.length, 42);
  body.set(room, 43);
  const mac = createHmac("sha256", key).update(body).digest();
  return Buffer.concat([body, mac]).toString("base64url");
}
