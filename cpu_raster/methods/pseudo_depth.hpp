// The notes' pseudo-depth and its inverse (lecture-clipping-fill-zbuffer.txt "Pseudo-depth",
// "pz At near and far", "What if you Want Depth?"). The camera sits at the origin looking down
// -z; near and far are the eye-space z of the two planes, both negative (the notes' example:
// near = -25, far = -75):
//
//   pz = 2 far near / ((far - near) z) - (far + near) / (far - near)      pz(near) = 1, pz(far) = -1
//   z  = 2 far near / ((far - near) pz + far + near)
//
// Larger pz is nearer: the notes' z-buffer starts at -1.0 (the far plane) and keeps the larger
// value. This is the OpenGL canonical-view-volume depth with the sign of the notes' matrix, not
// Vulkan's 0..1 window depth.
//
// Does: the two formulas. Does not: clamp, or accept near == far or z == 0 (std::invalid_argument).
#pragma once

namespace rastercmp::methods {

double pseudo_depth(double z_eye, double near_z, double far_z);
double eye_z_from_pseudo_depth(double pseudo, double near_z, double far_z);

}  // namespace rastercmp::methods
