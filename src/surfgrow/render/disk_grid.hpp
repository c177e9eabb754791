// Disks binned in cubes, for the picture's questions about which disks lie near each other.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow::render {

/// Points (disk centres) binned in cubes of one side. Cube coordinates are clamped to +-2^40, so
/// a stray point at 1e300 lands in an end cube instead of overflowing; non-finite points are left
/// out. Cubes are numbered in order of their first point: same input, same numbering.
class DiskGrid {
  public:
    static constexpr std::uint32_t kNone = UINT32_MAX;

    /// `cube`: the side; unless it is > 0 and finite, every point is left out.
    DiskGrid(std::span<const Vec3d> centers, double cube);

    [[nodiscard]] std::size_t cubes() const { return coords_.size(); }
    /// The cube of point `i`, or kNone for a point left out.
    [[nodiscard]] std::uint32_t cube_of(std::size_t i) const { return cube_of_[i]; }
    /// The points in cube `c`, in increasing order.
    [[nodiscard]] std::span<const std::uint32_t> points_in(std::uint32_t c) const {
        return {members_.data() + first_[c], members_.data() + first_[c + 1]};
    }
    /// The cubes holding points within `reach` cubes of the cube of position `p` along every
    /// axis (that cube included), in a fixed order; none for a non-finite `p`.
    [[nodiscard]] std::vector<std::uint32_t> around(const Vec3d& p, int reach = 1) const;
    /// Every pair of cubes that touch (share a face, an edge or a corner), each pair once.
    [[nodiscard]] std::vector<std::pair<std::uint32_t, std::uint32_t>> touching() const;

  private:
    using Coord = std::array<std::int64_t, 3>;
    [[nodiscard]] Coord coord_of(const Vec3d& p) const;
    [[nodiscard]] std::uint32_t find(const Coord& c) const;

    double cube_ = 1.0;
    std::vector<Coord> coords_;           // per cube
    std::vector<std::uint32_t> cube_of_;  // per point
    std::vector<std::uint32_t> first_;    // per cube + 1: offsets into members_
    std::vector<std::uint32_t> members_;  // point ids grouped by cube
    // Open addressing over coords_: slot -> cube + 1 (0 empty).
    std::vector<std::uint32_t> slots_;
};

}  // namespace surfgrow::render
