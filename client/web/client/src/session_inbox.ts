// What a session received and has not handed out yet (snapshots, errors, pongs, the
// game's messages), each kept within its bound, and the counts of a client's
// traffic (ClientStats).
import { ClientStats, GameMessage, Pong, ServerError, Snapshot } from "./types.js";

/** Buffered errors, pongs and game messages are few in a healthy session; the bound
 * only stops a misbehaving server from growing them without limit. */
const MAX_SMALL_EVENTS = 256;

export function emptyStats(): ClientStats {
  return {
    bytesReceived: 0,
    bytesSent: 0,
    snapshotsReceived: 0,
    snapshotsDropped: 0,
    errorsReceived: 0,
    inputsSent: 0,
    recordsReceived: 0,
    acksSent: 0,
    desyncs: 0,
    viewHashesChecked: 0,
    fullStatesReceived: 0,
  };
}

export class SessionInbox {
  snapshots: Snapshot[] = [];
  errors: ServerError[] = [];
  pongs: Pong[] = [];
  gameMessages: GameMessage[] = [];

  /** maxSnapshots: past it, the oldest snapshot not taken is dropped. */
  constructor(
    private readonly stats: ClientStats,
    private readonly maxSnapshots: number,
  ) {}

  addSnapshot(snapshot: Snapshot): void {
    this.stats.snapshotsReceived += 1;
    this.stats.recordsReceived += snapshot.records;
    if (this.snapshots.length >= this.maxSnapshots) {
      this.snapshots.shift();
      this.stats.snapshotsDropped += 1;
    }
    this.snapshots.push(snapshot);
  }

  addError(error: ServerError): void {
    this.stats.errorsReceived += 1;
    if (this.errors.length >= MAX_SMALL_EVENTS) this.errors.shift();
    this.errors.push(error);
  }

  addPong(pong: Pong): void {
    if (this.pongs.length >= MAX_SMALL_EVENTS) this.pongs.shift();
    this.pongs.push(pong);
  }

  addGameMessage(message: GameMessage): void {
    if (this.gameMessages.length >= MAX_SMALL_EVENTS) this.gameMessages.shift();
    this.gameMessages.push(message);
  }

  /** The pongs not yet taken, oldest first; the inbox keeps none. */
  takePongs(): Pong[] {
    const pongs = this.pongs;
    this.pongs = [];
    return pongs;
  }

  /** The game's messages not yet taken, oldest first; the inbox keeps none. */
  takeGameMessages(): GameMessage[] {
    const messages = this.gameMessages;
    this.gameMessages = [];
    return messages;
  }
}
