// Scene primitives (bounded rectangles, boxes, cylinders) and the faces they are made of.
#pragma once

#include <cstdint>
#include <string>
#include <variant>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::scanner {

/// A bounded plane: the points center + a u_axis + b v_axis with |a| <= half_u_m, |b| <= half_v_m.
/// Its normal is u_axis x v_axis. It is seen from both sides (a plate of no thickness). The axes
/// need not be unit length (they are normalised) but must be perpendicular.
struct Rectangle {
    Vec3d center = Vec3d::Zero();
    Vec3d u_axis = Vec3d::UnitX();
    Vec3d v_axis = Vec3d::UnitY();
    double half_u_m = 0.5;  ///< half size along u_axis
    double half_v_m = 0.5;  ///< half size along v_axis
};

/// A solid oriented box; each of its 6 faces is its own face (ids in the order +x, -x, +y, -y,
/// +z, -z of the box's own axes, the columns of `rotation`).
struct Box {
    Vec3d center = Vec3d::Zero();
    Mat3d rotation = Mat3d::Identity();  ///< box axes in the world, as columns (a rotation)
    Vec3d half_size_m = Vec3d::Constant(0.5);

    /// An axis-aligned box between two corners.
    [[nodiscard]] static Box from_min_max(const Vec3d& lo, const Vec3d& hi) {
        return {0.5 * (lo + hi), Mat3d::Identity(), 0.5 * (hi - lo)};
    }
};

/// A solid circular cylinder between the centres of its two ends. Faces: the curved side first,
/// then (if capped) the disc at `base` and the disc at `top`.
struct Cylinder {
    Vec3d base = Vec3d::Zero();
    Vec3d top = Vec3d::UnitZ();
    double radius_m = 0.1;
    bool capped = true;  ///< false: an open tube (seen from inside too)
};

using Shape = std::variant<Rectangle, Box, Cylinder>;

/// One object of a scene; `name` is optional and only for people (errors, truth files).
struct Primitive {
    std::string name;
    Shape shape;
};

enum class FaceKind : std::uint8_t { kRectangle, kDisc, kCylinder };

/// One surface of a primitive with its own ground-truth id. Rectangles and discs are planar (the
/// paper's planes); a cylinder's curved side is not and carries its axis instead of a normal.
struct Face {
    std::int32_t id = -1;         ///< scene-wide face id (the label of the points on it)
    std::int32_t primitive = -1;  ///< index of its primitive in the scene description
    FaceKind kind = FaceKind::kRectangle;
    Vec3d center = Vec3d::Zero();   ///< rectangle / disc centre; cylinder: middle of its axis
    Vec3d normal = Vec3d::UnitZ();  ///< planar: outward unit normal; cylinder: unit axis
    Vec3d u_axis = Vec3d::UnitX();  ///< planar: unit in-plane axes with u x v = normal
    Vec3d v_axis = Vec3d::UnitY();
    double half_u_m = 0.0;  ///< rectangle: half size along u; disc and cylinder: radius
    double half_v_m = 0.0;  ///< rectangle: half size along v; disc: radius; cylinder: half length

    [[nodiscard]] bool planar() const { return kind != FaceKind::kCylinder; }
    /// The face's plane (planar faces; for a cylinder, the plane through its axis midpoint normal
    /// to the axis, which is not a surface of it).
    [[nodiscard]] Plane plane() const { return Plane::through(center, normal); }
    /// Outward unit normal at a point on (or near) the face: the plane normal, or for a cylinder's
    /// side the radial direction from its axis.
    [[nodiscard]] Vec3d normal_at(const Vec3d& p) const {
        if (planar()) return normal;
        const Vec3d w = p - center;
        const Vec3d radial = w - w.dot(normal) * normal;
        const double len = radial.norm();
        return len > 0.0 ? Vec3d(radial / len) : u_axis;
    }
};

}  // namespace surfgrow::scanner
