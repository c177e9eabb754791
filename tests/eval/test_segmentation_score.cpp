// Over- and under-segmentation counts against known labellings.
#include <gtest/gtest.h>

#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/segmentation_score.hpp"

namespace surfgrow::eval {
namespace {

std::vector<std::int32_t> repeat(std::initializer_list<std::pair<std::int32_t, int>> runs) {
    std::vector<std::int32_t> out;
    for (const auto& [label, n] : runs) out.insert(out.end(), std::size_t(n), label);
    return out;
}

TEST(SegmentationScore, CountsSplitsAndMerges) {
    // Face 0 (1000 points) split 600/400 across planes 0 and 1; faces 1 and 2 (500 each) merged
    // into plane 2; face 3 (300) found whole in plane 3 but for 10 points in plane 0 (noise);
    // face 4 has 100 points only: not scored.
    const auto truth = repeat({{0, 1000}, {1, 500}, {2, 500}, {3, 300}, {4, 100}});
    const auto found = repeat({{0, 600}, {1, 400}, {2, 1000}, {3, 290}, {0, 10}, {5, 100}});
    const SegmentationScore s = score_segmentation(truth, found);
    EXPECT_EQ(s.faces, 4u);
    EXPECT_EQ(s.over_segmented, 1u);
    EXPECT_EQ(s.over_faces, std::vector<std::int32_t>{0});
    EXPECT_EQ(s.under_segmented, 1u);
    EXPECT_EQ(s.under_segments, std::vector<std::int32_t>{2});
    EXPECT_EQ(s.one_to_one, 3u);  // faces 1, 2 and 3 each lie in one plane
    EXPECT_EQ(s.missed, 0u);
    EXPECT_NEAR(s.points_in_best, (600.0 + 500 + 500 + 290) / 2300, 1e-12);
}

TEST(SegmentationScore, UnlabelledPointsAreIgnored) {
    const auto truth = repeat({{-1, 500}, {0, 500}});
    const auto found = repeat({{0, 500}, {-1, 250}, {1, 250}});
    const SegmentationScore s = score_segmentation(truth, found);
    EXPECT_EQ(s.faces, 1u);  // 250 labelled in both
    EXPECT_EQ(s.over_segmented, 0u);
    EXPECT_EQ(s.under_segmented, 0u);
    EXPECT_THROW((void)score_segmentation(truth, std::vector<std::int32_t>(3, 0)), Error);
}

TEST(SegmentationScore, PiecesSplitAFaceAtItsGaps) {
    // One face in two clusters 50 mm apart; points 5 mm apart within each.
    std::vector<Vec3f> pts;
    std::vector<std::int32_t> truth;
    for (int i = 0; i < 20; ++i) {
        pts.emplace_back(0.005f * float(i), 0.0f, 0.0f);
        pts.emplace_back(0.15f + 0.005f * float(i), 0.0f, 0.0f);
        truth.push_back(7);
        truth.push_back(7);
    }
    pts.emplace_back(0.0f, 0.0f, 0.0f);
    truth.push_back(-1);
    const auto pieces = truth_pieces(pts, truth, 0.024);
    EXPECT_EQ(pieces[0], 0);
    EXPECT_EQ(pieces[1], 1);
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) EXPECT_EQ(pieces[i], std::int32_t(i % 2));
    EXPECT_EQ(pieces.back(), -1);
    EXPECT_EQ(truth_pieces(pts, truth, 0.2)[1], 0);  // bridged
}

}  // namespace
}  // namespace surfgrow::eval
