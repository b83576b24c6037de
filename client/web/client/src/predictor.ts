// The predictor both ends run bit for bit (docs/PROTOCOL.md 5.2). JavaScript never
// fuses a multiply and an add, and every operation below is one IEEE-754 double
// operation in the order the protocol gives: the result equals the server's mirror.

export enum PredictorMode {
  Ballistic = 0,
  Glide = 1,
  Hold = 2,
}

export const PREDICTOR_MODE_COUNT = 3;

/** A body as the client holds it: what it was sent, carried forward. */
export interface PredictedBody {
  id: bigint;
  /** The id's halves, for the view hash. */
  idHi: number;
  idLo: number;
  x: number;
  y: number;
  vx: number;
  vy: number;
  mode: PredictorMode;
}

export class Predictor {
  readonly dt: number;
  readonly halfDtSquared: number;

  constructor(
    tickRate: number,
    readonly gx: number,
    readonly gy: number,
  ) {
    this.dt = 1.0 / tickRate;
    this.halfDtSquared = 0.5 * this.dt * this.dt;
  }

  /** One tick of the body's mode. */
  advance(body: PredictedBody): void {
    const dt = this.dt;
    const h = this.halfDtSquared;
    switch (body.mode) {
      case PredictorMode.Ballistic:
        body.x = body.x + body.vx * dt + this.gx * h;
        body.y = body.y + body.vy * dt + this.gy * h;
        body.vx = body.vx + this.gx * dt;
        body.vy = body.vy + this.gy * dt;
        return;
      case PredictorMode.Glide:
        body.x = body.x + body.vx * dt;
        body.y = body.y + body.vy * dt;
        return;
      case PredictorMode.Hold:
        return;
    }
  }
}
