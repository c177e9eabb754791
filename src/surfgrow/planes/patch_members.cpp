#include "surfgrow/planes/patch_members.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

namespace surfgrow {

PatchMembers collect_patch_members(std::span<const Vec3f> points,
                                   std::span<const std::int32_t> labels, std::size_t surfaces,
                                   int threads) {
    // A counting sort in `parts` slices of the input: each slice counts its members per surface,
    // then writes them after the earlier slices' (input order within each surface, whichever
    // thread writes it).
    const std::size_t n = labels.size();
    const auto parts = static_cast<std::size_t>(std::max(1, threads));
    std::vector<std::vector<std::uint32_t>> at(parts, std::vector<std::uint32_t>(surfaces, 0));
    auto member = [&](std::size_t i) { return labels[i] >= 0 && is_finite(points[i]); };
    auto slice = [&](std::size_t k) { return std::pair{k * n / parts, (k + 1) * n / parts}; };
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (std::size_t k = 0; k < parts; ++k) {
        const auto [begin, end] = slice(k);
        for (std::size_t i = begin; i < end; ++i)
            if (member(i)) ++at[k][static_cast<std::size_t>(labels[i])];
    }
    PatchMembers m;
    m.offset.assign(surfaces + 1, 0);
    std::uint32_t next = 0;
    for (std::size_t s = 0; s < surfaces; ++s) {
        m.offset[s] = next;
        for (std::size_t k = 0; k < parts; ++k)  // slice k's count becomes its first slot
            next += std::exchange(at[k][s], next);
    }
    m.offset[surfaces] = next;
    m.index.resize(next);
    m.point.resize(next);
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (std::size_t k = 0; k < parts; ++k) {
        const auto [begin, end] = slice(k);
        for (std::size_t i = begin; i < end; ++i)
            if (member(i)) {
                const std::uint32_t j = at[k][static_cast<std::size_t>(labels[i])]++;
                m.index[j] = static_cast<std::uint32_t>(i);
                m.point[j] = points[i];
            }
    }
    return m;
}

PatchMembers extend_patch_members(PatchMembers old, std::span<const Vec3f> points,
                                  std::span<const std::int32_t> labels, std::size_t from,
                                  std::size_t surfaces) {
    const std::size_t n = labels.size();
    const std::size_t known = old.offset.empty() ? 0 : old.offset.size() - 1;
    // The new points' counts (few: one scan), then each list's new start.
    std::vector<std::uint32_t> at(surfaces, 0);
    auto member = [&](std::size_t i) { return labels[i] >= 0 && is_finite(points[i]); };
    for (std::size_t i = from; i < n; ++i)
        if (member(i)) ++at[static_cast<std::size_t>(labels[i])];
    std::vector<std::uint32_t> offset(surfaces + 1, 0);
    std::uint32_t next = 0;
    for (std::size_t s = 0; s < surfaces; ++s) {
        offset[s] = next;
        const std::uint32_t had = s < known ? old.offset[s + 1] - old.offset[s] : 0;
        next += had + std::exchange(at[s], next + had);  // at[s]: where its new points go
    }
    offset[surfaces] = next;
    // In place: the arrays grow (with room for a few more scans, so that most calls move no
    // memory to a new block and touch no new page), then each old list moves to its new start,
    // the last first. A list only moves towards the end, and never past the next one's new start,
    // so none overwrites a list still to move.
    if (old.index.capacity() < next) {
        old.index.reserve(next + next / 4);
        old.point.reserve(next + next / 4);
    }
    old.index.resize(next);
    old.point.resize(next);
    for (std::size_t s = known; s-- > 0;) {
        const std::uint32_t a = old.offset[s], len = old.offset[s + 1] - a;
        if (len == 0 || offset[s] == a) continue;
        std::copy_backward(old.index.begin() + a, old.index.begin() + a + len,
                           old.index.begin() + offset[s] + len);
        std::copy_backward(old.point.begin() + a, old.point.begin() + a + len,
                           old.point.begin() + offset[s] + len);
    }
    PatchMembers m = std::move(old);
    m.offset = std::move(offset);
    for (std::size_t i = from; i < n; ++i)
        if (member(i)) {
            const std::uint32_t j = at[static_cast<std::size_t>(labels[i])]++;
            m.index[j] = static_cast<std::uint32_t>(i);
            m.point[j] = points[i];
        }
    return m;
}

}  // namespace surfgrow
