#include "turn.hpp"

#include "ball.hpp"

namespace pge::oracle::detail {

std::vector<ExactVec> turned(const std::vector<ExactVec>& points, const Dyadic& theta) {
  if (theta.is_zero()) return points;
  // A few guard bits over kTurnBits: the ball's radius is then far below the bits kept.
  const Precision precision(kTurnBits + 16);
  Ball s, c;
  sin_cos(s, c, Ball(theta));
  std::vector<ExactVec> out;
  out.reserve(points.size());
  for (const ExactVec& r : points) {
    const Ball x(r.x), y(r.y);
    out.push_back({(c * x - s * y).mid(), (s * x + c * y).mid()});
  }
  return out;
}

}  // namespace pge::oracle::detail
