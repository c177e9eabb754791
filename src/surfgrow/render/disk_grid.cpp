#include "surfgrow/render/disk_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace surfgrow::render {

namespace {

constexpr double kClamp = 1099511627776.0;  // 2^40 cubes

std::uint64_t mix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

std::uint64_t hash_of(const std::array<std::int64_t, 3>& c) {
    std::uint64_t h = 0;
    for (const std::int64_t v : c) h = mix(h ^ static_cast<std::uint64_t>(v));
    return h;
}

}  // namespace

DiskGrid::Coord DiskGrid::coord_of(const Vec3d& p) const {
    Coord c{};
    for (int a = 0; a < 3; ++a)
        c[static_cast<std::size_t>(a)] =
            static_cast<std::int64_t>(std::floor(std::clamp(p[a] / cube_, -kClamp, kClamp)));
    return c;
}

std::uint32_t DiskGrid::find(const Coord& c) const {
    if (slots_.empty()) return kNone;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = hash_of(c) & mask;; s = (s + 1) & mask) {
        const std::uint32_t k = slots_[s];
        if (k == 0) return kNone;
        if (coords_[k - 1] == c) return k - 1;
    }
}

DiskGrid::DiskGrid(std::span<const Vec3d> centers, double cube)
    : cube_(cube), cube_of_(centers.size(), kNone) {
    const bool valid = cube > 0 && std::isfinite(cube);
    slots_.assign(std::bit_ceil(std::max<std::size_t>(16, 2 * centers.size())), 0);
    const std::size_t mask = slots_.size() - 1;
    std::vector<std::uint32_t> count;
    for (std::size_t i = 0; i < centers.size() && valid; ++i) {
        if (!centers[i].allFinite()) continue;
        const Coord c = coord_of(centers[i]);
        std::size_t s = hash_of(c) & mask;
        while (slots_[s] != 0 && coords_[slots_[s] - 1] != c) s = (s + 1) & mask;
        if (slots_[s] == 0) {
            coords_.push_back(c);
            count.push_back(0);
            slots_[s] = static_cast<std::uint32_t>(coords_.size());
        }
        cube_of_[i] = slots_[s] - 1;
        ++count[cube_of_[i]];
    }
    first_.assign(coords_.size() + 1, 0);
    for (std::size_t c = 0; c < coords_.size(); ++c) first_[c + 1] = first_[c] + count[c];
    members_.resize(first_.back());
    std::vector<std::uint32_t> next(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < centers.size(); ++i)
        if (cube_of_[i] != kNone) members_[next[cube_of_[i]]++] = static_cast<std::uint32_t>(i);
}

std::vector<std::uint32_t> DiskGrid::around(const Vec3d& p, int reach) const {
    std::vector<std::uint32_t> out;
    if (!p.allFinite() || !(cube_ > 0 && std::isfinite(cube_))) return out;
    const Coord o = coord_of(p);
    for (int dx = -reach; dx <= reach; ++dx)
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dz = -reach; dz <= reach; ++dz) {
                const std::uint32_t k = find({o[0] + dx, o[1] + dy, o[2] + dz});
                if (k != kNone) out.push_back(k);
            }
    return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> DiskGrid::touching() const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::uint32_t c = 0; c < coords_.size(); ++c) {
        const Coord& o = coords_[c];
        // The 13 neighbours that come after this cube in (x, y, z) order: each pair once.
        for (int dx = 0; dx <= 1; ++dx)
            for (int dy = dx == 0 ? 0 : -1; dy <= 1; ++dy)
                for (int dz = (dx == 0 && dy == 0) ? 1 : -1; dz <= 1; ++dz) {
                    const std::uint32_t k = find({o[0] + dx, o[1] + dy, o[2] + dz});
                    if (k != kNone) pairs.emplace_back(c, k);
                }
    }
    return pairs;
}

}  // namespace surfgrow::render
