// A cloud for the examples when no file is given: the inside corner of a room (floor and two
// walls, 1 m square each) sampled every 5 mm with 1 mm of noise, seen from (0.5, 0.5, 0.5) m.
#pragma once

#include <random>

#include "surfgrow/core/point_cloud.hpp"

namespace example {

inline surfgrow::PointCloud room_corner() {
    surfgrow::PointCloud cloud;
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.001f);
    for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 200; ++j) {
            const float a = 0.0025f + 0.005f * static_cast<float>(i);
            const float b = 0.0025f + 0.005f * static_cast<float>(j);
            cloud.points.emplace_back(a, b, noise(rng));  // floor, z = 0
            cloud.points.emplace_back(noise(rng), a, b);  // wall, x = 0
            cloud.points.emplace_back(a, noise(rng), b);  // wall, y = 0
        }
    cloud.viewpoint = surfgrow::Vec3d(0.5, 0.5, 0.5);  // normals face the sensor
    return cloud;
}

}  // namespace example
