// SegComp's correct detection against hand-made labellings with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/eval/face_detection.hpp"

namespace surfgrow::eval {
namespace {

// `n` points of face `f` found as segment `s`.
void add(std::vector<std::int32_t>& truth, std::vector<std::int32_t>& found, int n, std::int32_t f,
         std::int32_t s) {
    for (int i = 0; i < n; ++i) {
        truth.push_back(f);
        found.push_back(s);
    }
}

TEST(FaceDetection, OneSegmentPerFaceIsDetected) {
    std::vector<std::int32_t> t, f;
    add(t, f, 1000, 0, 0);
    add(t, f, 800, 1, 1);
    const FaceDetection d = correct_detections(t, f);
    EXPECT_EQ(d.faces, 2u);
    EXPECT_EQ(d.correct, 2u);
    EXPECT_DOUBLE_EQ(d.fraction(), 1.0);
}

TEST(FaceDetection, CoplanarPiecesOfOneFaceCountAsOne) {
    std::vector<std::int32_t> t, f;
    add(t, f, 600, 0, 0);  // one face split in two pieces, each wholly on it
    add(t, f, 400, 0, 1);
    EXPECT_EQ(correct_detections(t, f).correct, 1u);
}

TEST(FaceDetection, ASegmentSpanningTwoFacesDetectsNeither) {
    std::vector<std::int32_t> t, f;
    add(t, f, 600, 0, 0);
    add(t, f, 600, 1, 0);  // half of segment 0 on each face: under 80 % on either
    const FaceDetection d = correct_detections(t, f);
    EXPECT_EQ(d.faces, 2u);
    EXPECT_EQ(d.correct, 0u);
    EXPECT_EQ(d.missed, (std::vector<std::int32_t>{0, 1}));
}

TEST(FaceDetection, UnregisteredPointsCountAgainstTheFace) {
    std::vector<std::int32_t> t, f;
    add(t, f, 790, 0, 0);
    add(t, f, 210, 0, -1);  // 79 % found: not detected at T = 0.8
    EXPECT_EQ(correct_detections(t, f).correct, 0u);
    t.clear();
    f.clear();
    add(t, f, 810, 0, 0);
    add(t, f, 190, 0, -1);
    EXPECT_EQ(correct_detections(t, f).correct, 1u);
}

TEST(FaceDetection, SmallAndUnscoredFacesAreLeftOut) {
    std::vector<std::int32_t> t, f;
    add(t, f, 1000, 0, 0);
    add(t, f, 499, 1, 1);  // under 500 points
    add(t, f, 1000, 2, -1);
    const std::vector<std::uint8_t> scored = {1, 1, 0};  // face 2 is not planar, say
    const FaceDetection d = correct_detections(t, f, 0.8, 500, scored);
    EXPECT_EQ(d.faces, 1u);
    EXPECT_EQ(d.correct, 1u);
}

TEST(FaceDetection, BadInputIsRefused) {
    const std::vector<std::int32_t> a = {0, 0}, b = {0};
    EXPECT_THROW((void)correct_detections(a, b), Error);
    EXPECT_THROW((void)correct_detections(a, a, 0.5), Error);
    EXPECT_TRUE(std::isnan(FaceDetection{}.fraction()));
}

}  // namespace
}  // namespace surfgrow::eval
