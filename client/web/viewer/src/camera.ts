// The world-to-pixel mapping of physics-view (client/viewer/camera.h): world y points
// up, pixel y down,
//
//   px = width / 2 + (x - center.x) * scale
//   py = height / 2 - (y - center.y) * scale
//
// fitted to every body of the Welcome (the scene's extent) with a 5% margin.
import { type BodyShape, boxHalfSize } from "@physics/client";

export interface Camera {
  centerX: number;
  centerY: number;
  scale: number; // pixels per metre
  width: number;
  height: number;
}

export function fit(bodies: readonly BodyShape[], width: number, height: number): Camera {
  let minX = Infinity;
  let minY = Infinity;
  let maxX = -Infinity;
  let maxY = -Infinity;
  for (const body of bodies) {
    const h = boxHalfSize(body);
    if (!Number.isFinite(body.position.x) || !Number.isFinite(body.position.y)) continue;
    minX = Math.min(minX, body.position.x - h.x);
    maxX = Math.max(maxX, body.position.x + h.x);
    minY = Math.min(minY, body.position.y - h.y);
    maxY = Math.max(maxY, body.position.y + h.y);
  }
  if (!(maxX > minX) || !(maxY > minY)) return { centerX: 0, centerY: 0, scale: 20, width, height };
  const sx = width / ((maxX - minX) * 1.05);
  const sy = height / ((maxY - minY) * 1.05);
  return {
    centerX: (minX + maxX) / 2,
    centerY: (minY + maxY) / 2,
    scale: Math.min(Math.max(Math.min(sx, sy), 0.01), 100000),
    width,
    height,
  };
}

export function toPixel(camera: Camera, x: number, y: number): [number, number] {
  return [camera.width / 2 + (x - camera.centerX) * camera.scale, camera.height / 2 - (y - camera.centerY) * camera.scale];
}
