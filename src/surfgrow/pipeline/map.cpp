#include "surfgrow/pipeline/map.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/random.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

namespace surfgrow {

namespace {

// Packs a cell's coordinates (each within +-2^20) into one key.
std::int64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::int64_t kBias = std::int64_t{1} << 20, kMask = (std::int64_t{1} << 21) - 1;
    return ((x + kBias) & kMask) | (((y + kBias) & kMask) << 21) | (((z + kBias) & kMask) << 42);
}

}  // namespace

Map::Map(MapConfig config) : config_(std::move(config)), pipeline_(config_.pipeline) {
    if (!(config_.join_tolerance >= 1.0 && config_.join_tolerance <= 10.0))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"map: join tolerance ", std::to_string(config_.join_tolerance),
                         " outside 1..10"}));
    // Cells two radii of the paper's neighbourhood wide: a surface of radius mu spans 2 x 2 x 2.
    cell_ = 2 * pipeline_.config().grow.mu;
    result_.grow.stats.orientation = OrientationSource::kScanOrigins;
}

std::int64_t Map::cell_key(const Vec3d& p) const {
    return pack(static_cast<std::int64_t>(std::floor(p.x() / cell_)),
                static_cast<std::int64_t>(std::floor(p.y() / cell_)),
                static_cast<std::int64_t>(std::floor(p.z() / cell_)));
}

// Each surface from `from` on, in every cell its neighbourhood ball touches.
void Map::index_surfaces(std::size_t from) {
    const std::vector<Surface>& all = result_.grow.surfaces;
    for (std::size_t s = from; s < all.size(); ++s) {
        const Vec3d lo = ((all[s].home.array() - all[s].radius) / cell_).floor();
        const Vec3d hi = ((all[s].home.array() + all[s].radius) / cell_).floor();
        for (auto x = static_cast<std::int64_t>(lo.x()); x <= static_cast<std::int64_t>(hi.x());
             ++x)
            for (auto y = static_cast<std::int64_t>(lo.y()); y <= static_cast<std::int64_t>(hi.y());
                 ++y)
                for (auto z = static_cast<std::int64_t>(lo.z());
                     z <= static_cast<std::int64_t>(hi.z()); ++z)
                    cells_[pack(x, y, z)].push_back(static_cast<std::int32_t>(s));
    }
}

const PipelineResult& Map::add_scan(const CloudView& scan, const Vec3d& origin) {
    const std::size_t k = scans();
    if (k >= std::numeric_limits<std::uint32_t>::max() || !origin.allFinite())
        throw Error(ErrorCode::kInvalidParameter, "map: a scan origin that is not finite");
    if (k == 0) cloud_.offset = scan.offset;
    const Vec3d shift = scan.offset - cloud_.offset;
    const std::size_t first = cloud_.size();
    const std::size_t n = scan.size();
    labelled_ = labelled_ && scan.has_labels();
    cloud_.points.reserve(first + n);
    for (const Vec3f& p : scan.points)
        cloud_.points.push_back((p.cast<double>() + shift).cast<float>());
    cloud_.scan_index.insert(cloud_.scan_index.end(), n, static_cast<std::uint32_t>(k));
    cloud_.scan_origins.push_back(origin + shift);
    if (labelled_) {
        cloud_.labels.insert(cloud_.labels.end(), scan.labels.begin(), scan.labels.end());
    } else {
        cloud_.labels.clear();
    }

    GrowResult& g = result_.grow;
    std::vector<Surface>& surfaces = g.surfaces;
    g.labels.resize(first + n, -1);
    last_ = {};
    last_.scan = k;
    last_.points = n;

    // 1. Points that fit a surface already there join it: the nearest plane relative to its
    // tolerance, among surfaces whose neighbourhood holds the point. Each point alone: parallel.
    const Stopwatch join_watch;
    const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) \
    num_threads(resolve_threads(config_.pipeline.grow.threads))
    for (std::int64_t i = 0; i < count; ++i) {
        const std::size_t at = first + static_cast<std::size_t>(i);
        const Vec3d p = cloud_.points[at].cast<double>();
        if (!p.allFinite()) continue;
        const auto cell = cells_.find(cell_key(p));
        if (cell == cells_.end()) continue;
        double best = 1.0;
        std::int32_t chosen = -1;
        for (const std::int32_t s : cell->second) {
            const Surface& f = surfaces[static_cast<std::size_t>(s)];
            if ((p - f.home).squaredNorm() > f.radius * f.radius) continue;
            const double tol = config_.join_tolerance * f.tolerance;
            const double d = std::abs(f.normal.dot(p - f.centroid)) / tol;
            if (d <= best && (d < best || chosen < 0 || s < chosen)) best = d, chosen = s;
        }
        g.labels[at] = chosen;
    }
    for (std::size_t at = first; at < first + n; ++at) {
        const std::int32_t s = g.labels[at];
        if (s < 0) continue;
        ++last_.joined;
        Surface& f = surfaces[static_cast<std::size_t>(s)];
        ++f.point_count;
        f.bounds.add(cloud_.points[at].cast<double>());
    }
    last_.join_seconds = join_watch.seconds();

    // 2. The rest grow surfaces of their own, facing this scan's origin.
    const Stopwatch grow_watch;
    PointCloud rest;
    std::vector<std::size_t> where;
    rest.viewpoint = origin + shift;
    for (std::size_t at = first; at < first + n; ++at)
        if (g.labels[at] < 0) {
            rest.points.push_back(cloud_.points[at]);
            where.push_back(at);
        }
    GrowerConfig grow_config = config_.pipeline.grow;
    grow_config.seed = mix_seed(grow_config.seed, k);
    grow_config.progress = nullptr;
    const GrowResult grown = grow_surfaces(rest, grow_config);
    const auto base = static_cast<std::int32_t>(surfaces.size());
    surfaces.insert(surfaces.end(), grown.surfaces.begin(), grown.surfaces.end());
    for (std::size_t i = 0; i < where.size(); ++i)
        if (grown.labels[i] >= 0) {
            g.labels[where[i]] = base + grown.labels[i];
            ++last_.grown;
        }
    last_.new_surfaces = grown.surfaces.size();
    index_surfaces(static_cast<std::size_t>(base));
    last_.grow_seconds = grow_watch.seconds();

    // 3. The map's figures, then its robot outputs.
    GrowStats& st = g.stats;
    st.points_in += n;
    std::uint64_t valid = 0;
    for (const Vec3f& p : scan.points) valid += is_finite(p);
    st.valid_points += valid;
    st.invalid_points += n - valid;
    st.registered += last_.joined + last_.grown;
    st.registered_grown = st.registered;
    st.surfaces = surfaces.size();
    st.noise_points = st.valid_points - st.registered;
    st.seconds = {};
    st.seconds.grow = last_.join_seconds + last_.grow_seconds;
    const Stopwatch outputs_watch;
    const GrowStats keep = st;
    result_ = pipeline_.finish(cloud_, std::move(g), &memo_);  // g is result_.grow: taken, returned
    result_.grow.stats = keep;
    last_.outputs_seconds = outputs_watch.seconds();
    return result_;
}

}  // namespace surfgrow
