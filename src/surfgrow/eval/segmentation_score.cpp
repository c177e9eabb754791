#include "surfgrow/eval/segmentation_score.hpp"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "surfgrow/core/cube_index.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::eval {

namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];  // path halving
        i = parent[i];
    }
    return i;
}

}  // namespace

SegmentationScore score_segmentation(std::span<const std::int32_t> truth,
                                     std::span<const std::int32_t> found,
                                     const SegmentationScoreConfig& config) {
    if (truth.size() != found.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"segmentation score: ", std::to_string(truth.size()), " true labels but ",
                         std::to_string(found.size()), " found"}));
    std::vector<std::uint64_t> keys;
    for (std::size_t i = 0; i < truth.size(); ++i)
        if (truth[i] >= 0 && found[i] >= 0)
            keys.push_back((std::uint64_t(std::uint32_t(truth[i])) << 32) |
                           std::uint32_t(found[i]));
    std::sort(keys.begin(), keys.end());
    struct Cell {
        std::int32_t face, segment;
        std::uint64_t count;
    };
    std::vector<Cell> cells;
    std::unordered_map<std::int32_t, std::uint64_t> face_total, segment_total;
    for (std::size_t k = 0; k < keys.size();) {
        std::size_t e = k;
        while (e < keys.size() && keys[e] == keys[k]) ++e;
        const Cell c{std::int32_t(keys[k] >> 32), std::int32_t(keys[k] & 0xffffffffu), e - k};
        cells.push_back(c);
        face_total[c.face] += c.count;
        segment_total[c.segment] += c.count;
        k = e;
    }
    auto counts = [&](std::uint64_t overlap, std::uint64_t total) {
        return overlap >= config.min_overlap_points &&
               double(overlap) >= config.min_share * double(total);
    };
    SegmentationScore s;
    std::unordered_map<std::int32_t, std::uint64_t> face_hits, segment_hits, face_best;
    for (const Cell& c : cells) {
        const std::uint64_t ft = face_total[c.face], st = segment_total[c.segment];
        if (ft >= config.min_points && counts(c.count, ft)) ++face_hits[c.face];
        if (st >= config.min_points && counts(c.count, st)) ++segment_hits[c.segment];
        face_best[c.face] = std::max(face_best[c.face], c.count);
    }
    std::uint64_t scored_points = 0, best_points = 0;
    for (const auto& [face, total] : face_total) {
        if (total < config.min_points) continue;
        ++s.faces;
        scored_points += total;
        best_points += face_best[face];
        const std::uint64_t hits = face_hits.count(face) ? face_hits[face] : 0;
        if (hits == 0) ++s.missed;
        if (hits == 1) ++s.one_to_one;
        if (hits >= 2) s.over_faces.push_back(face);
    }
    for (const auto& [segment, total] : segment_total) {
        if (total < config.min_points) continue;
        ++s.segments;
        if (segment_hits.count(segment) && segment_hits[segment] >= 2)
            s.under_segments.push_back(segment);
    }
    std::sort(s.over_faces.begin(), s.over_faces.end());
    std::sort(s.under_segments.begin(), s.under_segments.end());
    s.over_segmented = s.over_faces.size();
    s.under_segmented = s.under_segments.size();
    s.points_in_best = scored_points ? double(best_points) / double(scored_points) : 0.0;
    return s;
}

std::vector<std::int32_t> truth_pieces(std::span<const Vec3f> points,
                                       std::span<const std::int32_t> truth, double link) {
    if (truth.size() != points.size())
        throw Error(ErrorCode::kInvalidParameter, "truth pieces: one label per point is needed");
    std::vector<std::uint8_t> include(points.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) include[i] = truth[i] >= 0;
    const CubeIndex index(points, link, include, 1);
    std::vector<std::uint32_t> parent(index.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto original = index.original_indices();
    const float r2 = static_cast<float>(link * link);
    std::vector<CubeIndex::Range> table;
    constexpr std::size_t kBatch = 4096;
    for (std::size_t c0 = 0; c0 < index.cube_count(); c0 += kBatch) {
        const std::size_t c1 = std::min(index.cube_count(), c0 + kBatch);
        index.neighbour_table(c0, c1, table);
        for (std::size_t c = c0; c < c1; ++c)
            for (std::uint32_t i = index.cube_begin(c); i < index.cube_end(c); ++i)
                for (std::size_t k = 0; k < 9; ++k) {
                    const CubeIndex::Range run = table[9 * (c - c0) + k];
                    for (std::uint32_t j = std::max(run.begin, i + 1); j < run.end; ++j)
                        if (truth[original[i]] == truth[original[j]] &&
                            (index.local_point(i) - index.local_point(j)).squaredNorm() <= r2)
                            parent[find_root(parent, i)] = find_root(parent, j);
                }
    }
    std::vector<std::int32_t> sorted_of(points.size(), -1);
    for (std::uint32_t i = 0; i < index.size(); ++i) sorted_of[original[i]] = std::int32_t(i);
    std::vector<std::int32_t> piece_of_root(index.size(), -1), out(points.size(), -1);
    std::int32_t next = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (sorted_of[i] < 0) continue;
        const std::uint32_t root = find_root(parent, std::uint32_t(sorted_of[i]));
        if (piece_of_root[root] < 0) piece_of_root[root] = next++;
        out[i] = piece_of_root[root];
    }
    return out;
}

}  // namespace surfgrow::eval
