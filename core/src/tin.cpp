// SPDX-License-Identifier: GPL-3.0-or-later
#include "tinlod/tin.h"

namespace tinlod {

double triangleArea(const Tin& tin, const Triangle& t) {
  const TinVertex& a = tin.vertices[t[0]];
  const TinVertex& b = tin.vertices[t[1]];
  const TinVertex& c = tin.vertices[t[2]];
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

double totalArea(const Tin& tin) {
  double sum = 0;
  for (const Triangle& t : tin.triangles) sum += triangleArea(tin, t);
  return sum;
}

}  // namespace tinlod
