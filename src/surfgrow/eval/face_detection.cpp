#include "surfgrow/eval/face_detection.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow::eval {

double FaceDetection::fraction() const {
    return faces ? static_cast<double>(correct) / static_cast<double>(faces)
                 : std::numeric_limits<double>::quiet_NaN();
}

FaceDetection correct_detections(std::span<const std::int32_t> truth,
                                 std::span<const std::int32_t> found, double tolerance,
                                 std::uint64_t min_points, std::span<const std::uint8_t> scored) {
    if (truth.size() != found.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"face detection: ", std::to_string(truth.size()), " true labels but ",
                         std::to_string(found.size()), " found"}));
    if (!(tolerance > 0.5 && tolerance <= 1))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"face detection: tolerance must lie in (0.5, 1], got ", num(tolerance)}));
    std::int32_t max_face = -1, max_segment = -1;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        max_face = std::max(max_face, truth[i]);
        max_segment = std::max(max_segment, found[i]);
    }
    std::vector<std::uint64_t> face_total(static_cast<std::size_t>(max_face + 1), 0);
    std::vector<std::uint64_t> segment_total(static_cast<std::size_t>(max_segment + 1), 0);
    std::vector<std::uint64_t> overlaps;  // (face << 32 | segment) of each point in both
    for (std::size_t i = 0; i < truth.size(); ++i) {
        if (truth[i] >= 0) ++face_total[static_cast<std::size_t>(truth[i])];
        if (found[i] >= 0) ++segment_total[static_cast<std::size_t>(found[i])];
        if (truth[i] >= 0 && found[i] >= 0)
            overlaps.push_back(std::uint64_t(std::uint32_t(truth[i])) << 32 |
                               std::uint32_t(found[i]));
    }
    std::sort(overlaps.begin(), overlaps.end());
    // Per face: the points held by segments that lie (>= T of themselves) on it.
    std::vector<std::uint64_t> held(face_total.size(), 0);
    for (std::size_t k = 0; k < overlaps.size();) {
        std::size_t e = k;
        while (e < overlaps.size() && overlaps[e] == overlaps[k]) ++e;
        const auto face = static_cast<std::size_t>(overlaps[k] >> 32);
        const auto segment = static_cast<std::size_t>(overlaps[k] & 0xffffffffu);
        const auto overlap = static_cast<double>(e - k);
        if (overlap >= tolerance * static_cast<double>(segment_total[segment])) held[face] += e - k;
        k = e;
    }
    FaceDetection d;
    for (std::size_t f = 0; f < face_total.size(); ++f) {
        if (face_total[f] < min_points) continue;
        if (!scored.empty() && (f >= scored.size() || !scored[f])) continue;
        ++d.faces;
        if (static_cast<double>(held[f]) >= tolerance * static_cast<double>(face_total[f]))
            ++d.correct;
        else
            d.missed.push_back(static_cast<std::int32_t>(f));
    }
    return d;
}

}  // namespace surfgrow::eval
