#include "surfgrow/render/framing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/render/disk_grid.hpp"

namespace surfgrow::render {

namespace {

constexpr double kTakeUntil = 0.8;    // share of the disks the largest pieces must hold
constexpr double kAlwaysTake = 0.05;  // a piece this large is structure, wherever it lies
constexpr double kNearShare = 0.1;    // pieces this close (share of the structure's size)

std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
}

}  // namespace

Framing parse_framing(std::string_view name) {
    if (name == "bulk") return Framing::kBulk;
    if (name == "all") return Framing::kAll;
    throw Error(ErrorCode::kInvalidParameter,
                cat({"framing '", std::string(name), "' is not bulk or all"}));
}

std::string_view framing_name(Framing framing) {
    return framing == Framing::kBulk ? "bulk" : "all";
}

bool usable(const Disk& d) {
    return d.center.allFinite() && d.normal.allFinite() && d.normal.squaredNorm() > 0 &&
           d.radius > 0 && std::isfinite(d.radius);
}

double median_disk_radius(std::span<const Disk> disks) {
    std::vector<double> r;
    r.reserve(disks.size());
    for (const Disk& d : disks)
        if (usable(d)) r.push_back(d.radius);
    if (r.empty()) return 0.0;
    auto mid = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
    std::nth_element(r.begin(), mid, r.end());
    return *mid;
}

std::vector<std::uint8_t> bulk_disks(std::span<const Disk> disks) {
    std::vector<Vec3d> centers(disks.size(), Vec3d::Constant(NAN));
    std::size_t total = 0;
    for (std::size_t i = 0; i < disks.size(); ++i)
        if (usable(disks[i])) centers[i] = disks[i].center, ++total;
    std::vector<std::uint8_t> keep(disks.size(), 0);
    if (total == 0) return keep;
    const DiskGrid grid(centers, kLinkRadii * median_disk_radius(disks));

    // Pieces: cubes joined through touching cubes.
    std::vector<std::uint32_t> parent(grid.cubes());
    std::iota(parent.begin(), parent.end(), 0u);
    for (const auto& [a, b] : grid.touching()) {
        const std::uint32_t ra = root(parent, a), rb = root(parent, b);
        if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
    std::vector<std::size_t> size(grid.cubes(), 0);
    for (std::uint32_t c = 0; c < grid.cubes(); ++c)
        size[root(parent, c)] += grid.points_in(c).size();
    std::vector<std::uint32_t> order;
    for (std::uint32_t c = 0; c < grid.cubes(); ++c)
        if (root(parent, c) == c) order.push_back(c);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return size[a] > size[b]; });
    std::vector<std::uint8_t> taken(grid.cubes(), 0);
    std::size_t held = 0;
    for (const std::uint32_t p : order) {
        const double share = double(size[p]) / double(total);
        if (double(held) / double(total) >= kTakeUntil && share < kAlwaysTake) continue;
        taken[p] = 1;
        held += size[p];
    }
    // Pieces within reach of what was taken are part of it (the far end of a wall where the
    // scan thins out): those whose box meets the taken box grown by kNearShare of its largest
    // side.
    std::vector<Vec3d> lo(grid.cubes(), Vec3d::Constant(INFINITY));
    std::vector<Vec3d> hi(grid.cubes(), Vec3d::Constant(-INFINITY));
    Vec3d taken_lo = Vec3d::Constant(INFINITY), taken_hi = Vec3d::Constant(-INFINITY);
    for (std::size_t i = 0; i < disks.size(); ++i) {
        if (grid.cube_of(i) == DiskGrid::kNone) continue;
        const std::uint32_t p = root(parent, grid.cube_of(i));
        const Vec3d r = Vec3d::Constant(disks[i].radius);
        lo[p] = lo[p].cwiseMin(disks[i].center - r), hi[p] = hi[p].cwiseMax(disks[i].center + r);
        if (taken[p])
            taken_lo = taken_lo.cwiseMin(disks[i].center - r),
            taken_hi = taken_hi.cwiseMax(disks[i].center + r);
    }
    const Vec3d grow = Vec3d::Constant(kNearShare * (taken_hi - taken_lo).maxCoeff());
    taken_lo -= grow, taken_hi += grow;
    for (const std::uint32_t p : order)
        if (!taken[p] && (lo[p].array() <= taken_hi.array()).all() &&
            (hi[p].array() >= taken_lo.array()).all())
            taken[p] = 1;
    for (std::size_t i = 0; i < disks.size(); ++i)
        if (grid.cube_of(i) != DiskGrid::kNone) keep[i] = taken[root(parent, grid.cube_of(i))];
    return keep;
}

}  // namespace surfgrow::render
