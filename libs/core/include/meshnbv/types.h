#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, quaternions
#include <array>
#include <cstdint>

namespace meshnbv {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Face = std::array<int, 3>;
using Rgb8 = std::array<std::uint8_t, 3>;

}  // namespace meshnbv
