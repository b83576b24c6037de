// What a Client is made with (ClientConfig), and the same with every default filled
// in, as the client reads it.
import { WebSocketConstructor } from "./socket.js";
import { ContactSubscription, PROTOCOL_VERSION, ViewRequest } from "./types.js";

export interface ClientConfig {
  /** ws://HOST:PORT/ of the server's --ws-port. */
  url: string;
  /** The WebSocket to use; default: the global one (browsers, node 22+). In node 20,
   * pass the `ws` package's. */
  WebSocket?: WebSocketConstructor;
  name?: string;
  /** Hello.access_token; none sent when empty. */
  token?: string;
  /** Sent in Hello; only tests of the version refusal change it. */
  protocolVersion?: number;
  /** Messages from the server larger than this end the session (ProtocolError).
   * Default 1 MiB. */
  maxMessageBytes?: number;
  /** Snapshots received and not yet taken are kept up to this count; older ones are
   * dropped (and counted). Default 4096. */
  maxBufferedSnapshots?: number;
  /** When nothing has been sent for this long (ms), a Ping goes, so that a client
   * that only watches is not dropped as idle. 0 turns it off. Default 2000. */
  keepaliveMs?: number;
  view?: ViewRequest;
  spectate?: boolean;
  seat?: number;
  contacts?: ContactSubscription;
  /** The clock snapshots and pongs are stamped with (ms). Default performance.now. */
  now?: () => number;
}

/** A ClientConfig with its defaults filled in (the WebSocket apart). */
export type ResolvedConfig = Required<Omit<ClientConfig, "WebSocket" | "view" | "seat" | "contacts">> &
  Pick<ClientConfig, "view" | "seat" | "contacts">;

export function resolveConfig(config: ClientConfig): ResolvedConfig {
  return {
    url: config.url,
    name: config.name ?? "physics-client-web",
    token: config.token ?? "",
    protocolVersion: config.protocolVersion ?? PROTOCOL_VERSION,
    maxMessageBytes: config.maxMessageBytes ?? 1 << 20,
    maxBufferedSnapshots: config.maxBufferedSnapshots ?? 4096,
    keepaliveMs: config.keepaliveMs ?? 2000,
    now: config.now ?? (() => performance.now()),
    view: config.view,
    spectate: config.spectate ?? false,
    seat: config.seat,
    contacts: config.contacts,
  };
}
