#include "physics/body.h"

namespace phys {

std::string_view describe(BodyDefError error) {
  switch (error) {
    case BodyDefError::None:
      return "ok";
    case BodyDefError::NonFinitePosition:
      return "position is not a finite number";
    case BodyDefError::NonFiniteVelocity:
      return "velocity is not a finite number";
    case BodyDefError::NonFiniteAcceleration:
      return "acceleration is not a finite number";
    case BodyDefError::BadRadius:
      return "radius must be a finite number > 0";
    case BodyDefError::BadHalfExtents:
      return "half extents must be finite numbers > 0";
    case BodyDefError::BadMass:
      return "a dynamic body's mass must be a finite number > 0";
    case BodyDefError::BadRestitution:
      return "restitution must be a finite number in [0, 1]";
    case BodyDefError::BadFriction:
      return "friction must be finite numbers >= 0";
    case BodyDefError::OutOfBounds:
      return "the body lies outside the world's bounds (or beyond |coordinate| 1e7)";
    case BodyDefError::TooLarge:
      return "the body is larger than the world's size limit";
    case BodyDefError::TooManyBodies:
      return "the world holds its maximum number of bodies";
    case BodyDefError::KinematicAcceleration:
      return "a kinematic body moves by its velocity alone: its acceleration must be zero";
    case BodyDefError::BadName:
      return "the name is longer than 256 bytes";
  }
  return "unknown error";
}

}  // namespace phys
