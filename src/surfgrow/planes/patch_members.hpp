// Which points each patch holds: the member lists bound planes, their adjacency and fragments
// read, built once from the grow labels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "surfgrow/core/geometry.hpp"

namespace surfgrow {

/// Member points of each surface in input order, as CSR offsets and indices, and their
/// coordinates in the same order: the passes over a patch's members stream them instead of
/// gathering them from the whole cloud (a cache miss per point on a map of millions). Points with
/// a non-finite coordinate belong to no surface here.
struct PatchMembers {
    std::vector<std::uint32_t> offset;  ///< surfaces + 1
    std::vector<std::uint32_t> index;   ///< point indices, surface by surface
    std::vector<Vec3f> point;           ///< point[k] = the cloud's point index[k]
    [[nodiscard]] std::span<const std::uint32_t> of(std::size_t s) const {
        return {index.data() + offset[s], offset[s + 1] - offset[s]};
    }
    [[nodiscard]] std::span<const Vec3f> points_of(std::size_t s) const {
        return {point.data() + offset[s], offset[s + 1] - offset[s]};
    }
};

/// The members of `surfaces` surfaces from labels (-1: none; every label < surfaces); the same
/// for any thread count.
[[nodiscard]] PatchMembers collect_patch_members(std::span<const Vec3f> points,
                                                 std::span<const std::int32_t> labels,
                                                 std::size_t surfaces, int threads = 1);

/// collect_patch_members(points, labels, surfaces) where `old` already holds the members of the
/// first `from` points (a map's last call: its surfaces only gain points, at the cloud's end):
/// old's lists move, in place, to their new starts and the points from `from` on are appended.
/// `old` describes at most `surfaces` surfaces and from <= labels.size(); the caller checks that
/// it is the same cloud.
[[nodiscard]] PatchMembers extend_patch_members(PatchMembers old, std::span<const Vec3f> points,
                                                std::span<const std::int32_t> labels,
                                                std::size_t from, std::size_t surfaces);

}  // namespace surfgrow
