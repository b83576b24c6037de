// The game side of the viewer: keys bound to game messages (the `keys` URL parameter,
// docs/WEB.md) and the last game messages received, for the panel.
import type { GameMessage } from "@physics/client";

/** The server takes at most this many bytes of payload (docs/PROTOCOL.md 3.9). */
export const MAX_PAYLOAD_BYTES = 256;
/** The panel shows this many messages, the newest last. */
export const SHOWN_MESSAGES = 5;

const NAMED = new Set(["space", "enter", "tab", "backspace"]);

/** A key's name as the map spells it: KeyboardEvent.key lower-cased, "space" for the
 * space bar. The names a map may bind: a-z, 0-9, space, enter, tab, backspace,
 * f1-f12 (the arrow keys steer). */
export function keyName(key: string): string {
  return key === " " ? "space" : key.toLowerCase();
}

export function bindable(name: string): boolean {
  return /^[a-z0-9]$/.test(name) || NAMED.has(name) || /^f([1-9]|1[0-2])$/.test(name);
}

/** "space:jump,x:shoot" -> key name -> payload bytes. Bindings that do not parse are
 * left out and said in `errors`. */
export function parseKeyMap(text: string | null): { map: Map<string, Uint8Array>; errors: string[] } {
  const map = new Map<string, Uint8Array>();
  const errors: string[] = [];
  if (!text) return { map, errors };
  for (const item of text.split(",")) {
    const colon = item.indexOf(":");
    const name = colon < 0 ? "" : item.slice(0, colon).trim().toLowerCase();
    const payload = new TextEncoder().encode(colon < 0 ? "" : item.slice(colon + 1));
    if (colon < 0) errors.push(`'${item}' is not KEY:PAYLOAD`);
    else if (!bindable(name)) errors.push(`unknown key '${name}'`);
    else if (payload.length === 0) errors.push(`key '${name}' has no payload`);
    else if (payload.length > MAX_PAYLOAD_BYTES) errors.push(`key '${name}': over ${MAX_PAYLOAD_BYTES} bytes`);
    else if (map.has(name)) errors.push(`key '${name}' is bound twice`);
    else map.set(name, payload);
  }
  return { map, errors };
}

/** A payload as text when it is UTF-8, else as hex ("hex 01ff"). */
export function payloadText(payload: Uint8Array): string {
  try {
    return new TextDecoder("utf-8", { fatal: true }).decode(payload);
  } catch {
    return `hex ${Array.from(payload, (b) => b.toString(16).padStart(2, "0")).join("")}`;
  }
}

export class GameLog {
  sent = 0;
  received = 0;
  recent: { tick: number; text: string }[] = [];

  add(messages: readonly GameMessage[]): void {
    for (const message of messages) {
      this.received += 1;
      this.recent.push({ tick: message.tick, text: payloadText(message.payload) });
      if (this.recent.length > SHOWN_MESSAGES) this.recent.shift();
    }
  }

  lines(): string[] {
    return [`game messages: ${this.sent} sent, ${this.received} received`, ...this.recent.map((m) => `  tick ${m.tick}: ${m.text.slice(0, 60)}`)];
  }
}
