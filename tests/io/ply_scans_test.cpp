// PLY: the scan each point came from and the scans' origins (fused clouds), written on request
// and read back so that `surfgrow grow` can turn normals toward each point's own sensor.
#include <string>

#include "io_test_helpers.hpp"
#include "support/test_support.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/ply.hpp"

namespace surfgrow::test {
namespace {

using io::PlyEncoding;
using io::read_ply;
using io::write_ply;

constexpr PlyEncoding kAllEncodings[] = {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian,
                                         PlyEncoding::kBinaryBigEndian};

// A cloud fused from `scans` scans: point i from scan i % scans, origins a metre apart.
PointCloud fused_cloud(std::size_t n, std::uint32_t scans) {
    PointCloud c = sample_cloud(n, 4, true, true);
    for (std::size_t i = 0; i < n; ++i)
        c.scan_index.push_back(static_cast<std::uint32_t>(i % scans));
    for (std::uint32_t k = 0; k < scans; ++k)
        c.scan_origins.emplace_back(0.1 * k - 0.5, 0.25, 1.45);
    if (scans == 1) c.viewpoint = c.scan_origins.front();
    return c;
}

std::string ply_of(const PointCloud& cloud, PlyEncoding enc, bool scans) {
    return written([&](std::ostream& out) { write_ply(out, cloud, enc, true, scans); });
}

TEST(PlyScans, RoundTripInEveryEncoding) {
    for (const std::uint32_t scans : {1u, 3u}) {
        const PointCloud cloud = fused_cloud(300, scans);
        for (PlyEncoding enc : kAllEncodings) {
            SCOPED_TRACE(std::string(io::to_string(enc)) + " " + std::to_string(scans));
            const PointCloud back = read_ply(ply_of(cloud, enc, true), "fused.ply");
            expect_same_cloud(cloud, back, 0.0);
            EXPECT_EQ(back.scan_index, cloud.scan_index);
            EXPECT_EQ(back.scan_origins, cloud.scan_origins);  // exact: shortest round-trip text
            EXPECT_EQ(back.viewpoint, cloud.viewpoint);
        }
    }
}

TEST(PlyScans, HeaderCarriesOneCommentPerOriginAndAUintProperty) {
    const std::string text = ply_of(fused_cloud(5, 2), PlyEncoding::kAscii, true);
    EXPECT_NE(text.find("comment surfgrow scan_origin 0 -0.5 0.25 1.45\n"), std::string::npos);
    EXPECT_NE(text.find("comment surfgrow scan_origin 1 -0.4 0.25 1.45\n"), std::string::npos);
    EXPECT_NE(text.find("property int label\nproperty uint scan\nend_header"), std::string::npos);
}

TEST(PlyScans, NotWrittenUnlessAskedSoEarlierFilesAreUnchanged) {
    const PointCloud cloud = fused_cloud(50, 2);
    PointCloud plain = cloud;
    plain.scan_index.clear();
    plain.scan_origins.clear();
    for (PlyEncoding enc : kAllEncodings) {
        const std::string bytes = ply_of(cloud, enc, false);
        EXPECT_EQ(bytes, ply_of(plain, enc, false));
        EXPECT_TRUE(read_ply(bytes, "plain.ply").scan_index.empty());
    }
}

TEST(PlyScans, GeoreferencedOriginsStayRelativeToTheOffset) {
    PointCloud cloud = georeferenced_cloud(40, 5);
    for (std::size_t i = 0; i < cloud.size(); ++i) cloud.scan_index.push_back(i % 2 ? 1u : 0u);
    cloud.scan_origins = {Vec3d(1.5, -2.0, 3.0), Vec3d(-4.0, 0.5, 2.0)};
    const PointCloud back = read_ply(ply_of(cloud, PlyEncoding::kBinaryLittleEndian, true), "g");
    ASSERT_NE(back.offset, Vec3d::Zero());  // the reader's own offset (its first large point)
    ASSERT_EQ(back.scan_origins.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const Vec3d expected = cloud.scan_origins[k] + cloud.offset;
        EXPECT_LT((back.scan_origins[k] + back.offset - expected).norm(), 1e-6);
    }
}

TEST(PlyScans, ReadScansOffLeavesThemOut) {
    io::ReadOptions options;
    options.read_scans = false;
    const PointCloud back =
        read_ply(ply_of(fused_cloud(20, 2), PlyEncoding::kBinaryLittleEndian, true), "f", options);
    EXPECT_TRUE(back.scan_index.empty());
    EXPECT_TRUE(back.scan_origins.empty());
    EXPECT_EQ(back.size(), 20u);
}

TEST(PlyScans, AScanPropertyWithoutOriginsIsSomeoneElsesAndIgnored) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nproperty uint scan\nend_header\n0 0 0 7\n1 1 1 9\n";
    const PointCloud c = read_ply(text, "other.ply");
    EXPECT_EQ(c.size(), 2u);
    EXPECT_TRUE(c.scan_index.empty());
}

TEST(PlyScans, InconsistentScanDataIsMalformed) {
    const std::string head = "ply\nformat ascii 1.0\n";
    const std::string vertex =
        "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
    struct Case {
        std::string text;
        std::string needle;
    };
    const Case cases[] = {
        {head + "comment surfgrow scan_origin 0 0 0 1\n" + vertex + "end_header\n0 0 0\n1 1 1\n",
         "no scan"},
        {head + "comment surfgrow scan_origin 0 0 0 1\n" + vertex +
             "property uint scan\nend_header\n0 0 0 0\n1 1 1 1\n",
         "scan 1"},
        {head + "comment surfgrow scan_origin 1 0 0 1\n" + vertex +
             "property uint scan\nend_header\n0 0 0 0\n1 1 1 0\n",
         "scan origin 1"},
        {head + "comment surfgrow scan_origin 0 0 zero 1\n" + vertex +
             "property uint scan\nend_header\n0 0 0 0\n1 1 1 0\n",
         "scan_origin"},
        {head + "comment surfgrow scan_origin 0 0 0 1\n" + vertex +
             "property float scan\nend_header\n0 0 0 0.5\n1 1 1 0\n",
         "scan 0.5"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        expect_error([&] { (void)read_ply(c.text, "bad.ply"); }, ErrorCode::kMalformedInput,
                     c.needle);
    }
}

TEST(PlyScans, WriteCloudKeepsThemOnlyWhenAsked) {
    TempDir dir;
    const PointCloud cloud = fused_cloud(30, 3);
    io::WriteOptions options;
    options.write_scans = true;
    io::write_cloud(dir / "with.ply", cloud, options);
    io::write_cloud(dir / "without.ply", cloud);
    EXPECT_EQ(io::read_cloud(dir / "with.ply").scan_index, cloud.scan_index);
    EXPECT_TRUE(io::read_cloud(dir / "without.ply").scan_index.empty());
}

}  // namespace
}  // namespace surfgrow::test
