// @physics/client: a client of physics-server over WebSocket (docs/WEB.md).
export { Client } from "./client.js";
export type { ClientConfig } from "./client.js";
export * from "./types.js";
export { PlayoutBuffer, defaultPlayoutSettings, validatePlayoutSettings } from "./playout.js";
export type { PlayoutBody, PlayoutFrame, PlayoutSettings, PlayoutStats, PlayoutStatus, PushResult } from "./playout.js";
export { Predictor, PredictorMode } from "./predictor.js";
export type { PredictedBody } from "./predictor.js";
export { Reconstruction, MAX_TICK_GAP, decodeIdGaps } from "./reconstruction.js";
export type { Quantum } from "./reconstruction.js";
export { Fnv64, doubleBits, doubleFromBits } from "./words.js";
export { globalWebSocket } from "./socket.js";
export type { WebSocketConstructor, WebSocketLike } from "./socket.js";
export * as wire from "./gen/wire_pb.js";
export { InputClock, defaultInputClockConfig } from "./input_clock.js";
export type { InputClockConfig } from "./input_clock.js";
export { InputPacer, InputSchedule } from "./input_pacer.js";
export type { InputFor, PacerConfig, PacerStats } from "./input_pacer.js";
