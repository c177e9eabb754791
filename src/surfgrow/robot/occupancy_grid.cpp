#include "surfgrow/robot/occupancy_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow {

namespace {

bool less_cell(const CellCoords& a, const CellCoords& b) {
    if (a.x() != b.x()) return a.x() < b.x();
    if (a.y() != b.y()) return a.y() < b.y();
    return a.z() < b.z();
}

}  // namespace

OccupancyGrid::OccupancyGrid(const CubeIndex& index, std::span<const std::int32_t> labels,
                             double mu)
    : mu_(mu),
      cube_size_(index.cube_size()),
      inv_cube_(1.0 / index.cube_size()),
      origin_(index.origin()) {
    const auto original = index.original_indices();
    for (std::size_t c = 0; c < index.cube_count(); ++c) {
        std::uint32_t registered = 0;
        for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i) {
            const std::uint32_t k = original[i];
            if (k >= labels.size())
                throw Error(ErrorCode::kInternal, "occupancy grid: label index out of range");
            registered += labels[k] >= 0 ? 1u : 0u;
        }
        if (registered == 0) continue;
        // Grid coordinates (not ranks: cells are places); key order is (x, y, z) lexicographic.
        const Vec3d g = index.grid_coords(c);
        if (!(g.cwiseAbs().maxCoeff() < 2147483647.0))
            throw Error(
                ErrorCode::kCloudTooLarge,
                cat({"occupancy grid: the grown points span more than 2^31 cubes of ", num(mu),
                     " (far outlier points?); crop the workspace or use a larger mu"}));
        cells_.push_back(g.cast<int>());
        counts_.push_back(registered);
        registered_ += registered;
    }
}

void OccupancyGrid::add_registered(std::vector<CellCoords> cells) {
    if (cells.empty()) return;
    std::sort(cells.begin(), cells.end(), less_cell);
    std::vector<CellCoords> merged;
    std::vector<std::uint32_t> counts;
    merged.reserve(cells_.size() + cells.size());
    counts.reserve(cells_.size() + cells.size());
    std::size_t old = 0;
    for (std::size_t i = 0; i < cells.size();) {
        std::size_t j = i;
        while (j < cells.size() && cells[j] == cells[i]) ++j;
        for (; old < cells_.size() && less_cell(cells_[old], cells[i]); ++old) {
            merged.push_back(cells_[old]);
            counts.push_back(counts_[old]);
        }
        auto added = static_cast<std::uint32_t>(j - i);
        if (old < cells_.size() && cells_[old] == cells[i]) added += counts_[old++];
        merged.push_back(cells[i]);
        counts.push_back(added);
        i = j;
    }
    merged.insert(merged.end(), cells_.begin() + static_cast<std::ptrdiff_t>(old), cells_.end());
    counts.insert(counts.end(), counts_.begin() + static_cast<std::ptrdiff_t>(old), counts_.end());
    registered_ += cells.size();
    cells_ = std::move(merged);
    counts_ = std::move(counts);
}

CellCoords OccupancyGrid::cell_of(const Vec3d& p) const {
    // The index's rounding: world -> float local -> floor(local / side).
    const Vec3f local = (p - origin_).cast<float>();
    CellCoords c;
    for (int a = 0; a < 3; ++a) {
        const double v = std::floor(static_cast<double>(local[a]) * inv_cube_);
        c[a] = static_cast<int>(std::clamp(v, -2147483647.0, 2147483647.0));
    }
    return c;
}

bool OccupancyGrid::occupied_cell(const CellCoords& c) const {
    return std::binary_search(cells_.begin(), cells_.end(), c, less_cell);
}

bool OccupancyGrid::occupied(const Vec3d& p) const {
    if (!p.allFinite() || cells_.empty()) return false;
    return occupied_cell(cell_of(p));
}

Aabb OccupancyGrid::bounds() const {
    Aabb box;
    if (cells_.empty()) return box;
    Eigen::Vector3i lo = cells_.front(), hi = cells_.front();
    for (const CellCoords& c : cells_) {
        lo = lo.cwiseMin(c);
        hi = hi.cwiseMax(c);
    }
    box.add(origin_ + lo.cast<double>() * cube_size_);
    box.add(origin_ + (hi.cast<double>() + Vec3d::Ones()) * cube_size_);
    return box;
}

OccupancyGrid occupancy_grid(const CloudView& cloud, std::span<const std::int32_t> labels,
                             const GrowerConfig& config) {
    if (labels.size() != cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"occupancy grid: ", std::to_string(labels.size()), " labels for ",
                         std::to_string(cloud.size()), " points"}));
    const std::vector<std::uint8_t> mask = grown_point_mask(cloud, config);
    std::uint64_t labelled = 0;
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] < 0) continue;
        if (!mask[i])
            throw Error(ErrorCode::kInvalidParameter,
                        cat({"occupancy grid: point ", std::to_string(i),
                             " is registered but was not grown (NaN or outside the crop): the "
                             "labels or the parameters are not those of this cloud"}));
        ++labelled;
    }
    const int threads = resolve_threads(config.threads);
    const CubeIndex index(cloud.points, config.mu, mask, threads);
    OccupancyGrid grid(index, labels, config.mu);
    if (grid.registered_points() != labelled)
        throw Error(ErrorCode::kInternal, "occupancy grid: registered point count mismatch");
    return grid;
}

}  // namespace surfgrow
