#include "surfgrow/robot/occupancy_memo.hpp"

#include <cstring>
#include <vector>

#include "surfgrow/core/grown_points.hpp"

namespace surfgrow {

namespace {

bool same_box(const std::optional<Aabb>& a, const std::optional<Aabb>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (a->min == b->min && a->max == b->max);
}

bool same_crop(const WorkspaceCrop& a, const WorkspaceCrop& b) {
    return same_box(a.box, b.box) && a.radius == b.radius && a.center == b.center;
}

// Bitwise: a NaN point is the same NaN point.
bool same_point(const Vec3f& a, const Vec3f& b) {
    return std::memcmp(a.data(), b.data(), sizeof(float) * 3) == 0;
}

std::uint64_t registered_among(std::span<const std::int32_t> labels) {
    std::uint64_t n = 0;
    for (const std::int32_t l : labels) n += l >= 0 ? 1u : 0u;
    return n;
}

}  // namespace

std::optional<OccupancyGrid> extend_occupancy(OccupancyMemo& memo, const CloudView& cloud,
                                              std::span<const std::int32_t> labels,
                                              const GrowerConfig& config) {
    const std::size_t from = memo.points;
    if (!memo.grid || from == 0 || from > cloud.size() || labels.size() != cloud.size() ||
        memo.grown_box.empty() || memo.grid->mu() != config.mu ||
        !same_crop(memo.crop, config.crop))
        return std::nullopt;
    if (config.crop.active() && crop_centre(cloud, config) != memo.crop_centre) return std::nullopt;
    if (!same_point(cloud.points[from - 1], memo.last) || labels[from - 1] != memo.last_label ||
        registered_among(labels.first(from)) != memo.registered)
        return std::nullopt;

    // The new points' grown ones, by the grower's own rule (the view keeps the crop's centre).
    CloudView tail;
    tail.points = cloud.points.subspan(from);
    tail.offset = cloud.offset;
    tail.viewpoint = cloud.viewpoint;
    const std::vector<std::uint8_t> grown = grown_point_mask(tail, config);
    Aabb box = memo.grown_box;
    for (std::size_t i = 0; i < tail.size(); ++i)
        if (grown[i]) box.add(tail.points[i].cast<double>());
    if (box.min != memo.grown_box.min) return std::nullopt;  // the origin moves: index anew

    const OccupancyGrid& grid = *memo.grid;
    std::vector<CellCoords> cells;
    for (std::size_t i = 0; i < tail.size(); ++i) {
        if (labels[from + i] < 0) continue;
        // A registered point the grower did not index: not this cloud's labels; the index
        // anew says so.
        if (!grown[i]) return std::nullopt;
        const CellCoords c = grid.cell_of(tail.points[i].cast<double>());
        if (c.maxCoeff() >= 2147483647) return std::nullopt;  // ditto: too far (cell_of clamps)
        cells.push_back(c);
    }
    memo.registered += cells.size();
    memo.grid->add_registered(std::move(cells));
    memo.points = cloud.size();
    memo.grown_box = box;
    memo.last = cloud.points.back();
    memo.last_label = labels.back();
    return memo.grid;
}

void remember_occupancy(OccupancyMemo& memo, const CloudView& cloud,
                        std::span<const std::int32_t> labels, const Aabb& grown_box,
                        const OccupancyGrid& grid, const GrowerConfig& config) {
    memo = {};
    if (cloud.empty() || labels.size() != cloud.size()) return;
    memo.points = cloud.size();
    memo.grown_box = grown_box;
    memo.registered = registered_among(labels);
    memo.last = cloud.points.back();
    memo.last_label = labels.back();
    memo.crop = config.crop;
    if (config.crop.active()) memo.crop_centre = crop_centre(cloud, config);
    memo.grid = grid;
}

}  // namespace surfgrow
