// physics-view's colours (client/viewer/palette.h), so that both draw a world alike.
export type Rgb = readonly [number, number, number];

export const BACKGROUND: Rgb = [22, 24, 30];
export const STATIC: Rgb = [118, 124, 136]; // grey: walls, floors, steps
export const DYNAMIC: Rgb = [70, 160, 255]; // blue: moving
export const SLEEPING: Rgb = [120, 90, 170]; // violet: still in the two newest snapshots
export const OWN: Rgb = [255, 168, 40]; // orange: the own body
export const KINEMATIC: Rgb = [60, 200, 170]; // teal: moved by its velocity alone
// Sensors: this green at SENSOR_ALPHA over what is under them.
export const SENSOR: Rgb = [120, 230, 110];
export const SENSOR_ALPHA = 80 / 255;
export const OWN_MARKER: Rgb = [255, 255, 255]; // the ring around the own body
export const TEXT: Rgb = [235, 235, 235];

export function css([r, g, b]: Rgb, alpha = 1): string {
  return alpha === 1 ? `rgb(${r}, ${g}, ${b})` : `rgba(${r}, ${g}, ${b}, ${alpha})`;
}
