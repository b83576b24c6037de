#pragma once
// The viewer's colours, one per kind of body (docs/VIEWER.md). The screenshot test
// reads them from here to know what it must find at a body's pixel.
#include <cstdint>

namespace viewer {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  bool operator==(const Rgb&) const = default;
};

inline constexpr Rgb kBackground{22, 24, 30};
inline constexpr Rgb kStatic{118, 124, 136};    // grey: walls, floors, steps
inline constexpr Rgb kDynamic{70, 160, 255};    // blue: moving
inline constexpr Rgb kSleeping{120, 90, 170};   // violet: still in the two newest snapshots
inline constexpr Rgb kFollowed{255, 168, 40};   // orange: the body the camera follows
inline constexpr Rgb kKinematic{60, 200, 170};  // teal: moved by its velocity alone
// Sensors (they detect, push nothing): this green at kSensorAlpha over what is under
// them, with a one-pixel edge in the full colour.
inline constexpr Rgb kSensor{120, 230, 110};
inline constexpr std::uint8_t kSensorAlpha = 80;
// A ring around the body this viewer plays (labels are in kText).
inline constexpr Rgb kOwnMarker{255, 255, 255};
// A box's edge, one pixel inside it, in the background's colour: boxes stacked edge to
// edge read as boxes, not as one block.
inline constexpr Rgb kBoxOutline = kBackground;
inline constexpr Rgb kText{235, 235, 235};
inline constexpr Rgb kPanel{0, 0, 0};  // drawn at kPanelAlpha behind the text
inline constexpr std::uint8_t kPanelAlpha = 170;

}  // namespace viewer
