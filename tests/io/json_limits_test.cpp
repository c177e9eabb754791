// Every JSON reader refuses a document nested deeper than it can need before parsing it, so a
// hostile file of nested arrays cannot make nlohmann::json build a tree of millions of nodes
// (memory) or destroy it recursively (stack). docs/fuzzing.md, "Resource limits".
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/coverage_io.hpp"
#include "surfgrow/io/planes_io.hpp"
#include "surfgrow/io/poses_file.hpp"
#include "surfgrow/io/results_io.hpp"
#include "surfgrow/io/robot_file.hpp"
#include "surfgrow/io/scene_file.hpp"
#include "surfgrow/io/truth_faces_file.hpp"

namespace surfgrow::io {
namespace {

const std::function<void(std::string_view)> kReaders[] = {
    [](std::string_view t) { (void)parse_result_json(t, "surfaces.json"); },
    [](std::string_view t) { (void)parse_planes_json(t, "planes.json"); },
    [](std::string_view t) { (void)parse_coverage_json(t, "coverage.json"); },
    [](std::string_view t) { (void)parse_robot_json(t, "robot.json", {}); },
    [](std::string_view t) { (void)parse_scene_json(t, "scene.json"); },
    [](std::string_view t) { (void)parse_poses_file(t, "poses.json"); },
    [](std::string_view t) { (void)parse_truth_faces_json(t, "truth_faces.json"); },
};

void expect_refused(const std::string& text, const char* what) {
    for (const auto& read : kReaders) {
        try {
            read(text);
            ADD_FAILURE() << what << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kMalformedInput) << e.what();
            EXPECT_NE(std::string(e.what()).find("nested deeper"), std::string::npos) << e.what();
        }
    }
}

TEST(JsonLimits, DeeplyNestedArraysAreRefusedBeforeParsing) {
    // 10^7 levels: parsed, this would be ~10^7 nodes (hundreds of MB) per reader.
    expect_refused(std::string(10'000'000, '['), "10^7 nested arrays");
    expect_refused("{\"a\":" + std::string(100, '[') + std::string(100, ']') + "}", "100 levels");
}

TEST(JsonLimits, BracketsInStringsDoNotCount) {
    // A string full of brackets is not nesting: the reader gets to its own checks.
    const std::string text = "{\"format\": \"" + std::string(1000, '[') + "\"}";
    for (const auto& read : kReaders) {
        try {
            read(text);
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).find("nested deeper"), std::string::npos) << e.what();
        }
    }
}

TEST(JsonLimits, ADocumentThatWouldNotFitInMemoryIsRefusedBeforeParsing) {
    // 1 MB of JSON would take about 6 MB as a tree: over a 2 MB budget, each reader refuses it,
    // naming itself, before building the tree.
    ::setenv("SURFGROW_MEMORY_LIMIT", "2M", 1);
    const std::string text = "[" + std::string(1'000'000, ' ') + "]";
    for (const auto& read : kReaders) {
        try {
            read(text);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kCloudTooLarge) << e.what();
            EXPECT_NE(std::string(e.what()).find(".json: parsing"), std::string::npos) << e.what();
        }
    }
    ::unsetenv("SURFGROW_MEMORY_LIMIT");
}

}  // namespace
}  // namespace surfgrow::io
