#include "surfgrow/io/octomap_export.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <string>
#include <unordered_set>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::io {

namespace {

octomap::point3d to_point(const Vec3d& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

// The leaf key of `p`, or an error naming what lies out of OctoMap's range.
octomap::OcTreeKey key_of(const octomap::OcTree& tree, const Vec3d& p, const char* what) {
    octomap::OcTreeKey key;
    if (!p.allFinite() || !tree.coordToKeyChecked(p.x(), p.y(), p.z(), key))
        throw Error(ErrorCode::kCloudTooLarge,
                    cat({"environment.bt: ", what, " (", num(p.x()), ", ", num(p.y()), ", ",
                         num(p.z()), ") lies beyond OctoMap's range of 32768 cells of ",
                         num(tree.getResolution()), " each way from the frame origin"}));
    return key;
}

std::uint64_t leaves_at_full_depth(const octomap::OcTree& tree, bool occupied) {
    std::uint64_t n = 0;
    const unsigned max_depth = tree.getTreeDepth();
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        if (tree.isNodeOccupied(*it) != occupied) continue;
        n += std::uint64_t{1} << (3 * (max_depth - it.getDepth()));
    }
    return n;
}

// A leaf key in one integer (3 x 16 bits) for fast std hash sets (OctoMap's KeySet is tr1's).
std::uint64_t pack(const octomap::OcTreeKey& k) {
    return std::uint64_t{k[0]} | (std::uint64_t{k[1]} << 16) | (std::uint64_t{k[2]} << 32);
}

octomap::OcTreeKey unpack(std::uint64_t v) {
    return octomap::OcTreeKey(static_cast<octomap::key_type>(v & 0xffff),
                              static_cast<octomap::key_type>((v >> 16) & 0xffff),
                              static_cast<octomap::key_type>((v >> 32) & 0xffff));
}

using KeySet = std::unordered_set<std::uint64_t>;

}  // namespace

OctomapSummary write_octomap_bt(std::ostream& out, const OccupancyGrid& grid,
                                const PointCloud& cloud, std::span<const std::uint8_t> ray_mask,
                                const SensorOrigins& origins) {
    if (!(grid.mu() > 0))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"environment.bt: the resolution must be positive, got ", num(grid.mu())}));
    if (!ray_mask.empty() && ray_mask.size() != cloud.size())
        throw Error(ErrorCode::kInternal, "environment.bt: ray mask size differs from the cloud");
    octomap::OcTree tree(grid.mu());
    OctomapSummary summary;
    summary.resolution = grid.mu();
    summary.carving = origins.source;

    KeySet occupied;
    occupied.reserve(grid.size());
    for (const CellCoords& c : grid.cells())
        occupied.insert(pack(key_of(tree, grid.centre(c), "an occupied cube")));
    if (occupied.size() != grid.size())
        throw Error(ErrorCode::kInternal, "environment.bt: two cubes share an OctoMap leaf");

    std::vector<std::uint64_t> free;
    if (origins.known()) {
        // Rays per origin, one per distinct end leaf, to the end leaf's centre.
        std::vector<KeySet> ends(origins.origins.size());
        KeySet all_ends, carved;
        for (std::size_t i = 0; i < cloud.size(); ++i) {
            if (!is_finite(cloud.points[i]) || (!ray_mask.empty() && !ray_mask[i])) continue;
            const Vec3d* o = origins.origin_of(cloud, i);
            if (!o) continue;
            const std::uint64_t end = pack(key_of(tree, cloud.points[i].cast<double>(), "a point"));
            ends[static_cast<std::size_t>(o - origins.origins.data())].insert(end);
            all_ends.insert(end);
        }
        octomap::KeyRay ray;
        for (std::size_t k = 0; k < ends.size(); ++k) {
            if (ends[k].empty()) continue;
            (void)key_of(tree, origins.origins[k], "a sensor origin");
            const octomap::point3d from = to_point(origins.origins[k]);
            for (const std::uint64_t end : ends[k]) {
                if (!tree.computeRayKeys(from, tree.keyToCoord(unpack(end)), ray)) continue;
                ++summary.rays;
                for (const octomap::OcTreeKey& key : ray) carved.insert(pack(key));
            }
        }
        for (const std::uint64_t key : carved)
            if (!occupied.count(key) && !all_ends.count(key)) free.push_back(key);
    }

    // Values are set, not accumulated, so the tree does not depend on the hash sets' order.
    for (const std::uint64_t key : free)
        tree.setNodeValue(unpack(key), tree.getClampingThresMinLog(), true);
    for (const std::uint64_t key : occupied)
        tree.setNodeValue(unpack(key), tree.getClampingThresMaxLog(), true);
    tree.updateInnerOccupancy();
    // OcTree::writeBinary() less its " done." on stderr, and with the resolution at full
    // precision (the library prints 6 digits, so a resolution like 1/300 would read back off).
    tree.toMaxLikelihood();
    tree.prune();
    const auto precision = out.precision(17);
    out << "# Octomap OcTree binary file\n"
        << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
        << "# written by surfgrow: occupied = registered points' cubes, free = carved by rays\n"
        << "id " << tree.getTreeType() << "\nsize " << tree.size() << "\nres "
        << tree.getResolution() << "\ndata\n";
    out.precision(precision);
    tree.writeBinaryData(out);
    if (!out)
        throw Error(ErrorCode::kCannotWrite, "environment.bt: the OctoMap could not be written");
    summary.occupied = leaves_at_full_depth(tree, true);
    summary.free = leaves_at_full_depth(tree, false);
    return summary;
}

}  // namespace surfgrow::io
