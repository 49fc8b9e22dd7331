// pbrt-v4's --pixelmaterial x,y: what the camera ray through the pixel's centre hits, surface
// after surface (each hit's position, normals, distance from the camera, and the material with
// the directive and file:line that made it), printed instead of rendering.
#pragma once

#include "pbrt_ext/util/vecmath.h"

#include <ostream>

namespace pbrt {

class Scene;

// Throws std::runtime_error for a pixel outside the film or when the ray hits nothing.
void PrintPixelMaterial(const Scene &scene, Point2i pixel, std::ostream &out);

}  // namespace pbrt
