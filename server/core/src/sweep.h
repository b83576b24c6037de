#pragma once
// Time of impact along one axis. The per-axis recipe moves a body on Y, then on X,
// so during a move its path is one-dimensional: against a static body it touches
// when its centre crosses a level given by the two shapes (a face, or the point of
// a rounded corner straight across). Finding that crossing is a 1D root.
#include <optional>

#include "physics/settings.h"
#include "world_impl.h"

namespace phys {

// The centre coordinates along `axis` (0 = x, 1 = y) at which `mover` overlaps
// `obstacle`, with the mover's other coordinate where it is now. Empty when they
// cannot touch moving only along `axis` (or touch only edge to edge, within
// `side_tolerance` on the other axis: a side contact, the other axis' business).
struct Interval {
  double lo;
  double hi;
};
std::optional<Interval> overlap_interval(const Body& mover, const Body& obstacle, int axis,
                                         double side_tolerance);

// A body's free motion on one axis over one sub-step of length h.
struct AxisPath {
  Integrator integrator;
  double x0, v0, a, k, h;
  double x1, v1;  // the end of the step, from integrate_axis

  double position(double t) const;
  double velocity(double t) const;
  // The earliest t in (0, h] at which the path reaches `level`, coming from x0's
  // side (x0 != level). Empty if it never does within the step.
  std::optional<double> reaches(double level) const;
};

}  // namespace phys
