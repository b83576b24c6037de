// Reads docs/PROTOCOL.md, so that the tests check the bytes and values on the page.
import { readFileSync } from "node:fs";
import { fileURLToPath } from "node:url";

export const repoRoot = fileURLToPath(new URL("../../../../", import.meta.url));
// Whitespace as one space: sentences on the page wrap anywhere.
export const protocolDoc = readFileSync(`${repoRoot}docs/PROTOCOL.md`, "utf8").replace(/\s+/g, " ");

/** The bytes of the page's "On the wire: `...`" line that starts with `firstBytes`. */
export function wireBytesOnPage(firstBytes) {
  const match = protocolDoc.match(new RegExp("On the wire: `(" + firstBytes + "[0-9a-f ]*)`"));
  if (!match) throw new Error(`no "On the wire" line starting ${firstBytes} in docs/PROTOCOL.md`);
  return Uint8Array.from(match[1].trim().split(/\s+/).map((h) => parseInt(h, 16)));
}

/** The payload of a TCP frame: the bytes after its varint length prefix, checked. */
export function payloadOf(frame) {
  let length = 0;
  let shift = 0;
  let i = 0;
  for (;;) {
    const byte = frame[i++];
    length += (byte & 0x7f) * 2 ** shift;
    shift += 7;
    if (byte < 0x80) break;
  }
  if (frame.length - i !== length) throw new Error(`frame of ${frame.length} bytes says ${length} follow after ${i}`);
  return frame.subarray(i);
}

export function hex64(value) {
  return "0x" + value.toString(16).padStart(16, "0");
}
