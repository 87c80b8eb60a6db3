// The cube-map layout of the prepared environment, for the code that builds
// and checks it (not for per-ISA kernel files: environment_lanes.h is the
// lane version of the same mapping). Face f in +X, -X, +Y, -Y, +Z, -Z order;
// face coordinates (s, t) in [-1, 1] with s to the right and t down, as
// OpenGL's cube maps:
//   +X: (1, -t, -s)   -X: (-1, -t, s)   +Y: (s, 1, t)
//   -Y: (s, -1, -t)   +Z: (s, -t, 1)    -Z: (-s, -t, -1)
// Texel i of a face of size n covers s in [2i/n - 1, 2(i+1)/n - 1); a level
// stores each face as (n + 2)^2 texels with a one-texel border, so padded
// index p is texel p - 1 and the border texels continue the face's
// projection past its edge (their directions lie in the neighbouring faces).
#pragma once

#include <cmath>

namespace quadra::cube {

constexpr int kFaces = 6;

// The (unnormalized) direction of face coordinates (s, t) on `face`.
inline void faceDirection(int face, double s, double t, double d[3]) {
  switch (face) {
    case 0:
      d[0] = 1, d[1] = -t, d[2] = -s;
      break;
    case 1:
      d[0] = -1, d[1] = -t, d[2] = s;
      break;
    case 2:
      d[0] = s, d[1] = 1, d[2] = t;
      break;
    case 3:
      d[0] = s, d[1] = -1, d[2] = -t;
      break;
    case 4:
      d[0] = s, d[1] = -t, d[2] = 1;
      break;
    default:
      d[0] = -s, d[1] = -t, d[2] = -1;
      break;
  }
}

// The face a direction projects to (the major axis; ties go to x, then y)
// and its face coordinates.
inline int directionFace(const double d[3], double& s, double& t) {
  const double ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
  if (ax >= ay && ax >= az) {
    s = (d[0] > 0 ? -d[2] : d[2]) / ax, t = -d[1] / ax;
    return d[0] > 0 ? 0 : 1;
  }
  if (ay >= az) {
    s = d[0] / ay, t = (d[1] > 0 ? d[2] : -d[2]) / ay;
    return d[1] > 0 ? 2 : 3;
  }
  s = (d[2] > 0 ? d[0] : -d[0]) / az, t = -d[1] / az;
  return d[2] > 0 ? 4 : 5;
}

// Face coordinate of padded texel index p's centre on a face of size n.
inline double paddedCentre(int p, int n) {
  return (double(p) - 0.5) * 2.0 / n - 1.0;
}

// Solid angle of the face rectangle [s0, s1] x [t0, t1] (exact: the integral
// of (1 + s^2 + t^2)^(-3/2), whose antiderivative is atan2(st, sqrt(1 + s^2 + t^2))).
inline double rectangleSolidAngle(double s0, double t0, double s1, double t1) {
  const auto f = [](double s, double t) { return std::atan2(s * t, std::sqrt(1 + s * s + t * t)); };
  return f(s1, t1) - f(s0, t1) - f(s1, t0) + f(s0, t0);
}

}  // namespace quadra::cube
