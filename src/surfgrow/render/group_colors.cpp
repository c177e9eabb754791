#include "surfgrow/render/group_colors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/render/disk_grid.hpp"

namespace surfgrow::render {

namespace {

// Surfaces in touching cubes of this many median radii are neighbours: faces that meet at an
// edge always are, faces a hand's width apart usually not.
constexpr double kNeighbourRadii = 2.0;

}  // namespace

std::vector<Rgb> group_colors(const std::vector<Surface>& surfaces,
                              std::span<const std::int32_t> groups) {
    if (groups.size() != surfaces.size())
        throw Error(
            ErrorCode::kInvalidParameter,
            cat({"surface groups must be one per surface: got ", std::to_string(groups.size()),
                 " for ", std::to_string(surfaces.size()), " surfaces"}));
    // Dense numbers for the group ids that occur, in id order.
    std::vector<std::int32_t> ids;
    for (const std::int32_t g : groups)
        if (g >= 0) ids.push_back(g);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    auto dense = [&](std::int32_t g) {
        return static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), g) -
                                          ids.begin());
    };
    std::vector<std::uint32_t> group_of(surfaces.size(), UINT32_MAX);
    std::vector<std::size_t> size(ids.size(), 0);
    std::vector<Vec3d> centers(surfaces.size(), Vec3d::Constant(NAN));
    std::vector<double> radii;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        if (groups[i] < 0) continue;
        group_of[i] = dense(groups[i]);
        ++size[group_of[i]];
        const Surface& s = surfaces[i];
        if (s.home.allFinite() && std::isfinite(s.radius) && s.radius > 0) {
            centers[i] = s.home;
            radii.push_back(s.radius);
        }
    }
    double median = 0.0;
    if (!radii.empty()) {
        auto mid = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
        std::nth_element(radii.begin(), mid, radii.end());
        median = *mid;
    }

    // Neighbouring groups: in one cube, or in two that touch. (a, b) with a < b, and how often.
    const DiskGrid grid(centers, kNeighbourRadii * median);
    std::vector<std::vector<std::uint32_t>> in_cube(grid.cubes());
    for (std::uint32_t c = 0; c < grid.cubes(); ++c) {
        for (const std::uint32_t i : grid.points_in(c)) in_cube[c].push_back(group_of[i]);
        std::sort(in_cube[c].begin(), in_cube[c].end());
        in_cube[c].erase(std::unique(in_cube[c].begin(), in_cube[c].end()), in_cube[c].end());
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> contacts;
    auto meet = [&](const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
        for (const std::uint32_t x : a)
            for (const std::uint32_t y : b)
                if (x != y) contacts.emplace_back(std::min(x, y), std::max(x, y));
    };
    for (std::uint32_t c = 0; c < grid.cubes(); ++c) meet(in_cube[c], in_cube[c]);
    for (const auto& [a, b] : grid.touching()) meet(in_cube[a], in_cube[b]);
    std::sort(contacts.begin(), contacts.end());
    // Adjacency lists with contact counts, both ways.
    std::vector<std::vector<std::pair<std::uint32_t, std::size_t>>> next_to(ids.size());
    for (std::size_t k = 0; k < contacts.size();) {
        std::size_t e = k;
        while (e < contacts.size() && contacts[e] == contacts[k]) ++e;
        next_to[contacts[k].first].emplace_back(contacts[k].second, e - k);
        next_to[contacts[k].second].emplace_back(contacts[k].first, e - k);
        k = e;
    }

    // Greedy colouring, the largest groups first.
    std::vector<std::uint32_t> order(ids.size());
    for (std::uint32_t g = 0; g < order.size(); ++g) order[g] = g;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return size[a] > size[b]; });
    constexpr std::size_t kNoColour = kGroupPalette.size();
    std::vector<std::size_t> colour(ids.size(), kNoColour);
    std::array<std::size_t, kGroupPalette.size()> used{};  // groups of each colour so far
    for (const std::uint32_t g : order) {
        std::array<std::size_t, kGroupPalette.size()> touch{};
        for (const auto& [n, count] : next_to[g])
            if (colour[n] != kNoColour) touch[colour[n]] += count;
        // The colour its neighbours touch least; among equals the one used least so far, so
        // that faces near each other but not touching (the treads of a stair) differ too.
        std::size_t best = 0;
        for (std::size_t c = 1; c < kGroupPalette.size(); ++c)
            if (touch[c] < touch[best] || (touch[c] == touch[best] && used[c] < used[best]))
                best = c;
        colour[g] = best;
        ++used[best];
    }
    std::vector<Rgb> out(surfaces.size(), kUnassignedGrey);
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        if (group_of[i] != UINT32_MAX) out[i] = kGroupPalette[colour[group_of[i]]];
    return out;
}

}  // namespace surfgrow::render
