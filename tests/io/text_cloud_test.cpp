// Text clouds: separators, comments, header rows, .pts counts, offsets, and malformed rows.
#include <bit>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "io_test_helpers.hpp"
#include "surfgrow/io/text_cloud.hpp"

namespace surfgrow::test {
namespace {

using io::read_text_cloud;
using io::write_text_cloud;

std::vector<Vec3f> points_of(const std::string& text, const io::ReadOptions& options = {}) {
    return read_text_cloud(text, "t.xyz", options).points;
}

TEST(TextCloud, ReadsBlankCommaAndSemicolonSeparatedRows) {
    const std::vector<Vec3f> expected{{1, 2, 3}, {4.5f, -5, 6e3f}};
    EXPECT_EQ(points_of("1 2 3\n4.5\t-5   6e3\n"), expected);
    EXPECT_EQ(points_of("1,2,3\n4.5, -5 ,6e3\n"), expected);
    EXPECT_EQ(points_of("1;2;3\r\n+4.5;-5;6E3\r\n"), expected);
}

TEST(TextCloud, SkipsCommentsBlankLinesAndExtraColumns) {
    const std::string text =
        "# scan of a bridge girder\n\n1 2 3 0.5 255 0 0  # first\n   \n# more\n4 5 6 0.7 0 255 0\n";
    EXPECT_EQ(points_of(text), (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
}

TEST(TextCloud, HeaderRowSelectsColumnsByNameInAnyOrderAndCase) {
    const std::string text = "intensity,Z,Label,y,X\n0.5,3,7,2,1\n0.1,6,8,5,4\n";
    const PointCloud c = read_text_cloud(text, "h.csv");
    EXPECT_EQ(c.points, (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
    EXPECT_EQ(c.labels, (std::vector<int32_t>{7, 8}));
    io::ReadOptions off;
    off.read_labels = false;
    EXPECT_TRUE(read_text_cloud(text, "h.csv", off).labels.empty());
    // CloudCompare's "//X,Y,Z" and quoted names.
    EXPECT_EQ(points_of("//X,Y,Z,R,G,B\n1,2,3,0,0,0\n"), (std::vector<Vec3f>{{1, 2, 3}}));
    EXPECT_EQ(points_of("\"y\";\"x\";\"z\"\n2;1;3\n"), (std::vector<Vec3f>{{1, 2, 3}}));
}

TEST(TextCloud, WithoutNamedColumnsTheFirstThreeNumericColumnsAreXyz) {
    EXPECT_EQ(points_of("id a b c\np1 1 2 3\np2 4 5 6\n"),
              (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
    EXPECT_EQ(points_of("wall 1 2 3 steel\nwall 4 5 6 steel\n"),
              (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
}

TEST(TextCloud, PtsPointCountLineIsSkipped) {
    EXPECT_EQ(points_of("2\n1 2 3 -100 10 20 30\n4 5 6 -90 10 20 30\n"),
              (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
}

TEST(TextCloud, NaNAndInfinityAreKeptInPlace) {
    const PointCloud c = read_text_cloud("1 2 3\nnan NaN nan\n4 inf -inf\n", "n.xyz");
    ASSERT_EQ(c.size(), 3u);
    EXPECT_TRUE(std::isnan(c.points[1].y()));
    EXPECT_TRUE(std::isinf(c.points[2].y()));
    EXPECT_EQ(c.points[2].x(), 4.0f);
}

TEST(TextCloud, LargeCoordinatesGetAnOffsetAndKeepTheirDigits) {
    const PointCloud c =
        read_text_cloud("512345.123 5412345.456 312.789\n512346.5 5412344.25 313\n", "g.xyz");
    EXPECT_EQ(c.offset, Vec3d(512345, 5412345, 313));
    EXPECT_NEAR(absolute(c, 0).x(), 512345.123, 1e-6);
    EXPECT_NEAR(absolute(c, 0).y(), 5412345.456, 1e-6);
    EXPECT_NEAR(absolute(c, 1).y(), 5412344.25, 1e-6);
}

TEST(TextCloud, RoundTripsWithShortestDecimalsLabelsAndOffsets) {
    const PointCloud cloud = sample_cloud(300, 21, true, true);
    const std::string plain = written([&](std::ostream& o) { write_text_cloud(o, cloud); });
    PointCloud no_labels = cloud;
    no_labels.labels.clear();
    expect_same_cloud(no_labels, read_text_cloud(plain, "p.xyz"), 0.0);

    const std::string labelled =
        written([&](std::ostream& o) { write_text_cloud(o, cloud, ',', true); });
    EXPECT_EQ(labelled.rfind("x,y,z,label\n", 0), 0u);
    expect_same_cloud(cloud, read_text_cloud(labelled, "p.csv"), 0.0);

    const PointCloud geo = georeferenced_cloud(300, 22);
    const std::string g = written([&](std::ostream& o) { write_text_cloud(o, geo); });
    expect_same_cloud(geo, read_text_cloud(g, "g.xyz"), 1e-5);

    PointCloud one;
    one.points.emplace_back(0.1f, -2.0f, 1e-7f);
    EXPECT_EQ(written([&](std::ostream& o) { write_text_cloud(o, one); }), "0.1 -2 1e-07\n");
}

TEST(TextCloud, MalformedRowsNameTheFileAndLine) {
    expect_error([] { (void)read_text_cloud("1 2 3\n4 5\n", "scan.xyz"); },
                 ErrorCode::kMalformedInput,
                 "scan.xyz line 2: expected at least 3 values, found 2");
    expect_error([] { (void)read_text_cloud("1 2 3\n\n4 5 six\n", "scan.xyz"); },
                 ErrorCode::kMalformedInput, "scan.xyz line 3: 'six' in column 3 is not a number");
    expect_error([] { (void)read_text_cloud("1,2,3\n4,,6\n", "scan.csv"); },
                 ErrorCode::kMalformedInput, "scan.csv line 2: '' in column 2 is not a number");
    expect_error([] { (void)read_text_cloud("x y z label\n1 2 3 4.5\n", "l.txt"); },
                 ErrorCode::kMalformedInput, "l.txt line 2: label '4.5' is not a 32-bit integer");
    expect_error([] { (void)read_text_cloud("a b c\nd e f\n", "words.txt"); },
                 ErrorCode::kMalformedInput, "words.txt line 2: expected three numbers");
    expect_error([] { (void)read_text_cloud("# nothing\n\n", "none.txt"); },
                 ErrorCode::kMalformedInput, "none.txt: the file holds no points");
    expect_error([] { (void)read_text_cloud("", "empty.txt"); }, ErrorCode::kMalformedInput,
                 "empty.txt: the file is empty");
    expect_error(
        [] {
            (void)read_text_cloud(std::string(5000, ' ') + "1" + std::string(5000, ',') + "\n",
                                  "wide.csv");
        },
        ErrorCode::kMalformedInput, "wide.csv line 1: more than 4096 columns");
}

// ---- normals ---------------------------------------------------------------------------------

TEST(TextCloud, NormalsRoundTripBitForBitWithAndWithoutLabels) {
    PointCloud cloud = sample_cloud(300, 81, true, true);
    add_normals(cloud, 82);
    PointCloud no_labels = cloud;
    no_labels.labels.clear();

    const std::string plain = written([&](std::ostream& o) { write_text_cloud(o, cloud); });
    EXPECT_EQ(plain.rfind("x y z nx ny nz\n", 0), 0u);
    const PointCloud p = read_text_cloud(plain, "n.xyz");
    expect_same_cloud(no_labels, p, 0.0);
    expect_same_normals(cloud, p);

    const std::string labelled =
        written([&](std::ostream& o) { write_text_cloud(o, cloud, ',', true); });
    EXPECT_EQ(labelled.rfind("x,y,z,nx,ny,nz,label\n", 0), 0u);
    const PointCloud l = read_text_cloud(labelled, "n.csv");
    expect_same_cloud(cloud, l, 0.0);
    expect_same_normals(cloud, l);

    const std::string pts =
        written([&](std::ostream& o) { write_text_cloud(o, no_labels, ' ', true, true); });
    EXPECT_EQ(pts.rfind("300\nx y z nx ny nz\n", 0), 0u);
    expect_same_normals(cloud, read_text_cloud(pts, "n.pts"));

    PointCloud geo = georeferenced_cloud(200, 83);
    add_normals(geo, 84);
    const PointCloud g =
        read_text_cloud(written([&](std::ostream& o) { write_text_cloud(o, geo); }), "g.xyz");
    expect_same_cloud(geo, g, 1e-5);
    expect_same_normals(geo, g);
}

// The writers' shortest text for every float: read straight as float it comes back exactly.
// (Read as a double and then rounded to float, 7.038531e-26 comes back as the next float.)
TEST(TextCloud, NormalsOfRandomFloatBitsComeBackExactly) {
    PointCloud cloud;
    for (int i = 0; i < 100000; ++i) cloud.points.emplace_back(float(i), 0.0f, 0.0f);
    add_normals(cloud, 85);  // the special values at 1, 6, 11, 16
    std::mt19937_64 rng(86);
    for (std::size_t i = 20; i < cloud.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            cloud.normals[i][a] = std::bit_cast<float>(static_cast<uint32_t>(rng()));
        }
    }
    const PointCloud back =
        read_text_cloud(written([&](std::ostream& o) { write_text_cloud(o, cloud); }), "r.xyz");
    expect_same_normals(cloud, back);
}

TEST(TextCloud, WriteNormalsFalseWritesTheTextOfACloudWithoutNormals) {
    const PointCloud plain = sample_cloud(40, 87, true, true);
    PointCloud with = plain;
    add_normals(with, 88);
    for (bool labels : {false, true}) {
        const std::string left_out =
            written([&](std::ostream& o) { write_text_cloud(o, with, ' ', labels, false, false); });
        EXPECT_EQ(left_out,
                  written([&](std::ostream& o) { write_text_cloud(o, plain, ' ', labels); }));
        EXPECT_TRUE(read_text_cloud(left_out, "t.xyz").normals.empty());
    }
    // A file with normals read without them: the same points and labels.
    io::ReadOptions off;
    off.read_normals = false;
    const PointCloud back = read_text_cloud(
        written([&](std::ostream& o) { write_text_cloud(o, with, ';', true); }), "t.csv", off);
    EXPECT_TRUE(back.normals.empty());
    expect_same_cloud(plain, back, 0.0);
}

TEST(TextCloud, NormalsOfTheWrongCountAreRefusedBeforeWriting) {
    PointCloud cloud = sample_cloud(10, 89, false, false);
    cloud.normals.assign(1, Vec3f(0, 0, 1));
    for (bool write_normals : {true, false}) {
        std::ostringstream out;
        expect_error([&] { write_text_cloud(out, cloud, ' ', false, true, write_normals); },
                     ErrorCode::kInvalidParameter, "the cloud has 1 normals for 10 points");
        EXPECT_TRUE(out.str().empty());
    }
}

TEST(TextCloud, NormalColumnsAreReadByNameWhenAllThreeAreThere) {
    // CloudCompare's header, any order and case.
    const PointCloud c = read_text_cloud("//X,Y,Z,Nz,R,Nx,Ny\n1,2,3,0.5,255,-1,0\n", "cc.csv");
    EXPECT_EQ(c.points, (std::vector<Vec3f>{{1, 2, 3}}));
    EXPECT_EQ(c.normals, (std::vector<Vec3f>{{-1, 0, 0.5f}}));
    // Two of three, or no header: no normals.
    EXPECT_TRUE(read_text_cloud("x y z nx ny\n1 2 3 0 1\n", "two.xyz").normals.empty());
    EXPECT_TRUE(read_text_cloud("1 2 3 0 0 1\n", "bare.xyz").normals.empty());
    // Every row needs them, as numbers.
    expect_error([] { (void)read_text_cloud("x y z nx ny nz\n1 2 3 0 0 1\n4 5 6\n", "s.xyz"); },
                 ErrorCode::kMalformedInput, "s.xyz line 3: expected at least 6 values, found 3");
    expect_error([] { (void)read_text_cloud("x,y,z,nx,ny,nz\n1,2,3,0,,1\n", "e.csv"); },
                 ErrorCode::kMalformedInput, "e.csv line 2: normal '' in column 5 is not a number");
    io::ReadOptions off;
    off.read_normals = false;
    EXPECT_EQ(read_text_cloud("x,y,z,nx,ny,nz\n1,2,3,0,,1\n", "e.csv", off).points,
              (std::vector<Vec3f>{{1, 2, 3}}));
}

}  // namespace
}  // namespace surfgrow::test
