// Wire messages (generated from proto/wire.proto) to the client's plain objects, and
// the client's requests to wire messages.
import { create } from "@bufbuild/protobuf";
import * as wire from "./gen/wire_pb.js";
import type {
  BodyShape,
  ContactEvent,
  ContactSubscription,
  Encoding,
  Rect,
  ServerError,
  View,
  ViewRequest,
  Welcome,
  Vec2,
} from "./types.js";

const ENCODINGS: Encoding[] = ["predicted", "exact", "full", "inputs"];

function vec2(v: wire.Vec2 | undefined): Vec2 {
  return { x: v?.x ?? 0, y: v?.y ?? 0 };
}

function rect(r: wire.Rect): Rect {
  return { minX: r.minX, minY: r.minY, maxX: r.maxX, maxY: r.maxY };
}

export function shapeFromWire(b: wire.BodyShape): BodyShape {
  return {
    bodyId: b.bodyId,
    shape: b.shape === wire.ShapeType.SHAPE_CIRCLE ? "circle" : b.shape === wire.ShapeType.SHAPE_BOX ? "box" : "unspecified",
    radius: b.radius,
    halfExtents: vec2(b.halfExtents),
    isStatic: b.isStatic,
    isKinematic: b.isKinematic,
    isSensor: b.isSensor,
    position: vec2(b.position),
    mass: b.mass,
    restitution: b.restitution,
    friction: vec2(b.friction),
    name: b.name,
    motion: b.isStatic ? "static" : b.isKinematic ? "kinematic" : "dynamic",
    velocity: vec2(b.velocity),
    acceleration: vec2(b.acceleration),
    contactFriction: b.contactFriction,
    filter: { categoryBits: b.categoryBits ?? 1, maskBits: b.maskBits ?? 0xffffffff, group: b.group },
  };
}

function viewFromWire(v: wire.ViewRequest | undefined): View {
  return {
    encoding: ENCODINGS[v?.encoding ?? 0] ?? "predicted",
    positionPrecision: v?.positionPrecision ?? 0.001,
    velocityPrecision: v?.velocityPrecision ?? 0.001,
    positionTolerance: v?.positionTolerance ?? 0.01,
    velocityTolerance: v?.velocityTolerance ?? 0.1,
    snapshotInterval: v?.snapshotInterval ?? 1,
    window: v?.window ?? 12,
    interestRadius: v?.interest.case === "interestRadius" ? v.interest.value : undefined,
    interestRect: v?.interest.case === "interestRect" ? rect(v.interest.value) : undefined,
    byteBudget: v?.byteBudget ?? 0,
    stateHash: v?.stateHash ?? false,
    viewHashInterval: v?.viewHashInterval ?? 4,
  };
}

export function welcomeFromWire(w: wire.Welcome): Welcome {
  return {
    protocolVersion: w.protocolVersion,
    clientId: w.clientId,
    bodyId: w.bodyId,
    tickRate: w.tickRate,
    currentTick: Number(w.currentTick),
    bodies: w.bodies.map(shapeFromWire),
    gravity: vec2(w.gravity),
    maxAcceleration: w.maxAcceleration,
    lockstep: w.lockstep,
    maxTicksAhead: w.maxTicksAhead,
    sceneName: w.sceneName,
    view: viewFromWire(w.view),
    maxPlayers: w.maxPlayers,
    spectator: w.spectator,
    seat: w.seat,
    seats: w.seats,
  };
}

export function contactFromWire(e: wire.ContactEvent): ContactEvent {
  return {
    end: e.end,
    tick: Number(e.tick),
    bodyA: e.bodyA,
    bodyB: e.bodyB,
    point: vec2(e.point),
    normal: vec2(e.normal),
    closingSpeed: e.closingSpeed,
  };
}

export function errorFromWire(e: wire.Error): ServerError {
  const name = wire.ErrorCode[e.code] as string | undefined;
  return {
    code: name ? name.replace(/^ERROR_/, "") : String(e.code),
    rawCode: e.code,
    message: e.message,
    fatal: e.fatal,
  };
}

export function viewToWire(v: ViewRequest): wire.ViewRequest {
  const m = create(wire.ViewRequestSchema, {
    encoding: ENCODINGS.indexOf(v.encoding ?? "predicted") as wire.Encoding,
    positionPrecision: v.positionPrecision,
    velocityPrecision: v.velocityPrecision,
    positionTolerance: v.positionTolerance,
    velocityTolerance: v.velocityTolerance,
    snapshotInterval: v.snapshotInterval,
    window: v.window,
    byteBudget: v.byteBudget,
    stateHash: v.stateHash ?? false,
    viewHashInterval: v.viewHashInterval,
  });
  if (v.interestRadius !== undefined) {
    m.interest = { case: "interestRadius", value: v.interestRadius };
  } else if (v.interestRect !== undefined) {
    m.interest = { case: "interestRect", value: create(wire.RectSchema, v.interestRect) };
  }
  return m;
}

export function contactsToWire(c: ContactSubscription): wire.ContactSubscription {
  return create(wire.ContactSubscriptionSchema, { all: c.all ?? false, bodyIds: c.bodyIds ?? [] });
}
