#pragma once
// Small vocabulary types shared by every part of the library. The library works in SI units.
#include <Eigen/Dense>

namespace fem {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace fem
