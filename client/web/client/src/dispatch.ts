// The dispatch of a session's messages from the server: each one checked (binary,
// within the size limit, parsed, in its place in the session: Welcome once and
// first) and handed to the part of the session it is for. Anything a server may not
// send ends the session as a ProtocolError.
import { fromBinary } from "@bufbuild/protobuf";
import * as wire from "./gen/wire_pb.js";
import { errorFromWire, welcomeFromWire } from "./convert.js";
import { SessionInbox } from "./session_inbox.js";
import { SnapshotReader } from "./snapshot_reader.js";
import { messageBytes } from "./socket.js";
import { ClientStats, ConnectionState, ServerError, Welcome } from "./types.js";

/** What the dispatch reads and changes of the session (a Client). */
export interface DispatchTarget {
  readonly state: ConnectionState;
  readonly stats: ClientStats;
  readonly inbox: SessionInbox;
  readonly reader: SnapshotReader;
  readonly maxMessageBytes: number;
  now(): number;
  fail(state: ConnectionState, detail: string): void;
  /** The Welcome came: the session is Connected. */
  welcomed(welcome: Welcome): void;
  /** A fatal Error came, before the session fails by it. */
  fatalError(error: ServerError): void;
  /** Wakes the waits (after any message that was not refused). */
  notify(): void;
}

export function dispatch(session: DispatchTarget, data: unknown): void {
  const bytes = messageBytes(data);
  if (!bytes) {
    session.fail(ConnectionState.ProtocolError, "the server sent a text message");
    return;
  }
  session.stats.bytesReceived += bytes.length;
  if (bytes.length > session.maxMessageBytes) {
    session.fail(
      ConnectionState.ProtocolError,
      `server message of ${bytes.length} bytes is over the limit of ${session.maxMessageBytes}`,
    );
    return;
  }
  let message: wire.ServerMessage;
  try {
    message = fromBinary(wire.ServerMessageSchema, bytes);
  } catch {
    session.fail(ConnectionState.ProtocolError, "server sent a message that does not parse");
    return;
  }
  const kind = message.kind;
  switch (kind.case) {
    case "welcome": {
      if (session.state !== ConnectionState.AwaitingWelcome) {
        session.fail(ConnectionState.ProtocolError, "server sent a second Welcome");
        return;
      }
      const welcome = welcomeFromWire(kind.value);
      if (!(welcome.tickRate > 0) || !Number.isFinite(welcome.tickRate)) {
        session.fail(ConnectionState.ProtocolError, `server sent a tick rate of ${welcome.tickRate}`);
        return;
      }
      session.welcomed(welcome);
      break;
    }
    case "snapshot": {
      if (session.state !== ConnectionState.Connected) {
        session.fail(ConnectionState.ProtocolError, "server sent a Snapshot before Welcome");
        return;
      }
      const snapshot = session.reader.read(kind.value, bytes.length);
      // A snapshot that does not apply ends the session; the waits are woken all the same.
      if (typeof snapshot === "string") session.fail(ConnectionState.ProtocolError, snapshot);
      else session.inbox.addSnapshot(snapshot);
      break;
    }
    case "error": {
      const error = errorFromWire(kind.value);
      session.inbox.addError(error);
      if (error.fatal) {
        session.fatalError(error);
        session.fail(
          session.state === ConnectionState.AwaitingWelcome ? ConnectionState.Refused : ConnectionState.ConnectionLost,
          `${error.code}: ${error.message}`,
        );
        return;
      }
      break;
    }
    case "pong":
      session.inbox.addPong({
        nonce: kind.value.nonce,
        clientTimeNs: kind.value.clientTimeNs,
        serverTick: Number(kind.value.serverTick),
        receivedAt: session.now(),
      });
      break;
    case "gameMessage":
      session.inbox.addGameMessage({ tick: Number(kind.value.tick), payload: kind.value.payload });
      break;
    default:
      // A kind newer than this client: ignored, as proto3 intends.
      return;
  }
  session.notify();
}
