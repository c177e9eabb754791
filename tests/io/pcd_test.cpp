// PCD: the three DATA kinds, every field type, COUNT and padding fields, organized clouds,
// VIEWPOINT, and the header and body errors.
#include <liblzf/lzf.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "io_test_helpers.hpp"
#include "surfgrow/io/pcd.hpp"

namespace surfgrow::test {
namespace {

using io::PcdEncoding;
using io::read_pcd;
using io::write_pcd;

constexpr PcdEncoding kAllEncodings[] = {PcdEncoding::kAscii, PcdEncoding::kBinary,
                                         PcdEncoding::kBinaryCompressed};

std::string pcd_of(const PointCloud& cloud, PcdEncoding enc, bool labels = true) {
    return written([&](std::ostream& out) { write_pcd(out, cloud, enc, labels); });
}

// A header for fields described as "name size type count" quadruples.
std::string header(const std::string& fields, const std::string& sizes, const std::string& types,
                   const std::string& counts, std::size_t width, std::size_t height,
                   const std::string& data) {
    return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " +
           sizes + "\nTYPE " + types + "\nCOUNT " + counts + "\nWIDTH " + std::to_string(width) +
           "\nHEIGHT " + std::to_string(height) + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
           std::to_string(width * height) + "\nDATA " + data + "\n";
}

std::string lzf_block(const std::string& raw) {
    std::string out(raw.size() + raw.size() / 16 + 64, '\0');
    const unsigned used = lzf_compress(raw.data(), static_cast<unsigned>(raw.size()), out.data(),
                                       static_cast<unsigned>(out.size()));
    std::string block;
    append_little_endian<uint32_t>(block, used);
    append_little_endian<uint32_t>(block, static_cast<uint32_t>(raw.size()));
    return block + out.substr(0, used);
}

TEST(Pcd, RoundTripsEveryDataKindWithLabelsAndNaNInPlace) {
    const PointCloud cloud = sample_cloud(700, 11, true, true);
    for (PcdEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = pcd_of(cloud, enc);
        EXPECT_NE(bytes.find("FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F I\n"),
                  std::string::npos);
        const PointCloud back = read_pcd(bytes, "mem.pcd");
        expect_same_cloud(cloud, back, 0.0);
        EXPECT_FALSE(back.viewpoint.has_value());
    }
}

TEST(Pcd, LargeCoordinatesAreWrittenAsF8AndComeBackThroughAnOffset) {
    PointCloud cloud = georeferenced_cloud(800, 12);
    cloud.viewpoint = Vec3d(1.5, -2.5, 30);
    for (PcdEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = pcd_of(cloud, enc);
        EXPECT_NE(bytes.find("SIZE 8 8 8\nTYPE F F F\n"), std::string::npos);
        const PointCloud back = read_pcd(bytes, "geo.pcd");
        EXPECT_NE(back.offset, Vec3d::Zero());
        expect_same_cloud(cloud, back, 1e-5);
        ASSERT_TRUE(back.viewpoint.has_value());
        EXPECT_LT((*back.viewpoint + back.offset - (*cloud.viewpoint + cloud.offset)).norm(), 1e-6);
    }
}

TEST(Pcd, DefaultViewpointCarriesNoInformation) {
    const std::string base = header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "ascii") + "1 2 3\n";
    EXPECT_FALSE(read_pcd(base, "v.pcd").viewpoint.has_value());
    std::string moved = base;
    moved.replace(moved.find("VIEWPOINT 0 0 0 1 0 0 0"), 23, "VIEWPOINT 1 2 3 1 0 0 0");
    EXPECT_EQ(read_pcd(moved, "v.pcd").viewpoint, Vec3d(1, 2, 3));
    std::string rotated = base;
    rotated.replace(rotated.find("VIEWPOINT 0 0 0 1 0 0 0"), 23, "VIEWPOINT 0 0 0 0 1 0 0");
    EXPECT_EQ(read_pcd(rotated, "v.pcd").viewpoint, Vec3d(0, 0, 0));
}

// An organized 4 x 3 cloud with NaN holes keeps all 12 points in row-major order.
TEST(Pcd, OrganizedCloudKeepsEveryPointInOrder) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Vec3f> pts;
    for (int i = 0; i < 12; ++i) {
        pts.push_back(i % 5 == 1 ? Vec3f(nan, nan, nan) : Vec3f(float(i), float(-i), 0.5f * i));
    }
    std::string ascii = header("x y z", "4 4 4", "F F F", "1 1 1", 4, 3, "ascii");
    std::string raw;
    for (const Vec3f& p : pts) {
        ascii += std::isnan(p.x()) ? "nan nan nan\n"
                                   : std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
                                         std::to_string(p.z()) + "\n";
        for (int a = 0; a < 3; ++a) append_little_endian(raw, p[a]);
    }
    std::string soa;
    for (int a = 0; a < 3; ++a) {
        for (const Vec3f& p : pts) append_little_endian(soa, p[a]);
    }
    const std::string files[] = {
        ascii,
        header("x y z", "4 4 4", "F F F", "1 1 1", 4, 3, "binary") + raw,
        header("x y z", "4 4 4", "F F F", "1 1 1", 4, 3, "binary_compressed") + lzf_block(soa),
    };
    PointCloud expected;
    expected.points = pts;
    for (const std::string& f : files) expect_same_cloud(expected, read_pcd(f, "org.pcd"), 0.0);
}

// Fields before, between and after x y z with COUNT > 1, '_' padding, every type.
TEST(Pcd, SkipsOtherFieldsCountsAndPaddingInEveryDataKind) {
    const std::string fields = "normal_x _ x y z rgb label fpfh";
    const std::string sizes = "4 1 8 4 2 4 2 4";
    const std::string types = "F U F F I U U F";
    const std::string counts = "1 3 1 1 1 1 1 3";
    const double xs[2] = {1.25, -7.5};
    const float ys[2] = {2.5f, 8.0f};
    const int16_t zs[2] = {-3, 300};
    const uint16_t labels[2] = {9, 60000};
    std::string raw;
    for (int i = 0; i < 2; ++i) {
        append_little_endian(raw, 0.0f);
        raw.append(3, '\x7f');
        append_little_endian(raw, xs[i]);
        append_little_endian(raw, ys[i]);
        append_little_endian(raw, zs[i]);
        append_little_endian<uint32_t>(raw, 0xffffff);
        append_little_endian(raw, labels[i]);
        for (int k = 0; k < 3; ++k) append_little_endian(raw, 1.0f * k);
    }
    // binary_compressed: non-padding fields one after another, padding left out (as PCL does).
    std::string soa;
    for (int i = 0; i < 2; ++i) append_little_endian(soa, 0.0f);
    for (int i = 0; i < 2; ++i) append_little_endian(soa, xs[i]);
    for (int i = 0; i < 2; ++i) append_little_endian(soa, ys[i]);
    for (int i = 0; i < 2; ++i) append_little_endian(soa, zs[i]);
    for (int i = 0; i < 2; ++i) append_little_endian<uint32_t>(soa, 0xffffff);
    for (int i = 0; i < 2; ++i) append_little_endian(soa, labels[i]);
    for (int i = 0; i < 2; ++i) {
        for (int k = 0; k < 3; ++k) append_little_endian(soa, 1.0f * k);
    }
    const std::string ascii_body =
        "0 127 127 127 1.25 2.5 -3 16777215 9 0 1 2\n"
        "0 127 127 127 -7.5 8 300 16777215 60000 0 1 2\n";
    const std::string files[] = {
        header(fields, sizes, types, counts, 2, 1, "ascii") + ascii_body,
        header(fields, sizes, types, counts, 2, 1, "binary") + raw,
        header(fields, sizes, types, counts, 2, 1, "binary_compressed") + lzf_block(soa),
    };
    for (const std::string& f : files) {
        const PointCloud c = read_pcd(f, "fields.pcd");
        ASSERT_EQ(c.size(), 2u);
        EXPECT_EQ(c.points[0], Vec3f(1.25f, 2.5f, -3));
        EXPECT_EQ(c.points[1], Vec3f(-7.5f, 8, 300));
        EXPECT_EQ(c.labels, (std::vector<int32_t>{9, 60000}));
    }
}

TEST(Pcd, ReadsEveryFieldTypeAsCoordinates) {
    const char* types[][2] = {{"1", "I"}, {"2", "I"}, {"4", "I"}, {"8", "I"}, {"1", "U"},
                              {"2", "U"}, {"4", "U"}, {"8", "U"}, {"4", "F"}, {"8", "F"}};
    for (const auto& t : types) {
        SCOPED_TRACE(std::string(t[1]) + t[0]);
        const std::string s = std::string(t[0]) + " " + t[0] + " " + t[0];
        const std::string ty = std::string(t[1]) + " " + t[1] + " " + t[1];
        const std::string ascii = header("x y z", s, ty, "1 1 1", 1, 1, "ascii") + "1 2 100\n";
        EXPECT_EQ(read_pcd(ascii, "t.pcd").points.at(0), Vec3f(1, 2, 100));
        std::string bin = header("x y z", s, ty, "1 1 1", 1, 1, "binary");
        const std::size_t size = std::stoul(t[0]);
        for (int v : {1, 2, 100}) {
            if (t[1][0] == 'F') {
                size == 4 ? append_little_endian(bin, float(v))
                          : append_little_endian(bin, double(v));
            } else {
                const uint64_t u = static_cast<uint64_t>(v);
                bin.append(reinterpret_cast<const char*>(&u), size);  // little-endian host
            }
        }
        EXPECT_EQ(read_pcd(bin, "t.pcd").points.at(0), Vec3f(1, 2, 100));
    }
}

TEST(Pcd, AcceptsVersion06HeadersWithoutViewpointPointsOrCount) {
    const std::string v6 =
        "VERSION .6\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 1\nDATA ascii\n"
        "1 2 3\n4 5 6\n";
    EXPECT_EQ(read_pcd(v6, "v6.pcd").size(), 2u);
    const std::string points_only =
        "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\r\n1 2 3\r\n";
    EXPECT_EQ(read_pcd(points_only, "p.pcd").points.at(0), Vec3f(1, 2, 3));
}

TEST(Pcd, PclPaddingAfterBinaryDataIsTolerated) {
    const PointCloud cloud = sample_cloud(5, 13, false, false);
    const std::string bytes = pcd_of(cloud, PcdEncoding::kBinary) + std::string(4000, '\0');
    expect_same_cloud(cloud, read_pcd(bytes, "pad.pcd"), 0.0);
}

TEST(Pcd, HeaderErrorsAreMalformedAndNameTheFile) {
    const std::string body = "1 2 3\n";
    const struct {
        std::string text;
        std::string needle;
    } cases[] = {
        {"", "empty"},
        {"hello world\n", "not a PCD file"},
        {"# only a comment\n", "not a PCD file"},
        {"VERSION 0.7\nFIELDS x y z\n", "ends before its DATA line"},
        {header("x y z", "4 4", "F F F", "1 1 1", 1, 1, "ascii") + body, "SIZE has 2"},
        {header("x y z", "4 4 2", "F F F", "1 1 1", 1, 1, "ascii") + body, "TYPE 'F' and SIZE '2'"},
        {header("x y z", "4 4 -4", "F F F", "1 1 1", 1, 1, "ascii") + body, "SIZE '-4'"},
        {header("x y z", "4 4 4", "F F D", "1 1 1", 1, 1, "ascii") + body, "TYPE 'D'"},
        {header("x y z", "4 4 4", "F F F", "1 1 0", 1, 1, "ascii") + body, "COUNT '0'"},
        {header("x y z", "4 4 4", "F F F", "1 1 2", 1, 1, "ascii") + body, "field z has COUNT 2"},
        {header("x y w", "4 4 4", "F F F", "1 1 1", 1, 1, "ascii") + body, "no field z"},
        {header("x y x z", "4 4 4 4", "F F F F", "1 1 1 1", 1, 1, "ascii") + body,
         "field x appears twice"},
        {header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "lzma") + body, "unknown DATA kind"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n",
         "WIDTH 2 x HEIGHT 2 does not equal POINTS 3"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH -2\nDATA ascii\n", "WIDTH must be"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nDATA ascii\n", "neither WIDTH nor POINTS"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nVIEWPOINT 0 0\nDATA ascii\n",
         "VIEWPOINT needs 7 numbers"},
        {"FIELDS x y z\nFIELDS x y z\n", "a second FIELDS line"},
        {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nCOLOR red\nDATA ascii\n",
         "unknown header keyword 'COLOR'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string msg = expect_error([&] { (void)read_pcd(c.text, "bad.pcd"); },
                                             ErrorCode::kMalformedInput, c.needle);
        EXPECT_EQ(msg.rfind("bad.pcd", 0), 0u) << msg;
    }
}

TEST(Pcd, BodyErrorsSayWhatIsWrong) {
    const std::string a = header("x y z", "4 4 4", "F F F", "1 1 1", 3, 1, "ascii");
    // The header is 11 lines, so the points are lines 12 to 14.
    expect_error([&] { (void)read_pcd(a + "1 2 3\n4 5 6\n", "few.pcd"); },
                 ErrorCode::kMalformedInput,
                 "few.pcd: header says 3 points but the data ends after 2");
    expect_error([&] { (void)read_pcd(a + "1 2 3\n4 5 6\n7 8 9\n1 1 1\n", "many.pcd"); },
                 ErrorCode::kMalformedInput, "many.pcd line 15: more points than the 3");
    expect_error([&] { (void)read_pcd(a + "1 2 3\n4 5\n7 8 9\n", "cols.pcd"); },
                 ErrorCode::kMalformedInput, "cols.pcd line 13: expected 3 values, found 2");
    expect_error([&] { (void)read_pcd(a + "1 2 3\n4 5 6 7\n7 8 9\n", "cols.pcd"); },
                 ErrorCode::kMalformedInput, "cols.pcd line 13: expected 3 values, found more");
    expect_error([&] { (void)read_pcd(a + "1 2 3\n4 five 6\n7 8 9\n", "num.pcd"); },
                 ErrorCode::kMalformedInput, "num.pcd line 13: 'five' is not a number");
    // Blank lines between and after the points are fine.
    EXPECT_EQ(read_pcd(a + "1 2 3\n\n4 5 6\n7 8 9\n\n  \n", "blank.pcd").size(), 3u);

    const std::string b = header("x y z", "4 4 4", "F F F", "1 1 1", 1000, 1, "binary");
    expect_error([&] { (void)read_pcd(b + std::string(8000, '\1'), "cloud.pcd"); },
                 ErrorCode::kMalformedInput,
                 "cloud.pcd: header says 1000 points of 12 bytes but only 8000 bytes follow");
    const std::string one = header("x y z", "4 4 4", "F F F", "1 1 1", 1, 1, "binary");
    expect_error([&] { (void)read_pcd(one + std::string(12, '\0') + "junk", "tail.pcd"); },
                 ErrorCode::kMalformedInput, "tail.pcd: 4 bytes follow the data");
}

TEST(Pcd, CompressedBlocksThatLieOrAreCorruptAreRejected) {
    const std::string h = header("x y z", "4 4 4", "F F F", "1 1 1", 100, 1, "binary_compressed");
    std::string soa;
    for (int i = 0; i < 300; ++i) append_little_endian(soa, 0.25f * float(i % 17));
    const std::string good = lzf_block(soa);
    EXPECT_EQ(read_pcd(h + good, "ok.pcd").size(), 100u);

    auto with_sizes = [&](uint32_t compressed, uint32_t uncompressed) {
        std::string s = good;
        std::memcpy(s.data(), &compressed, 4);
        std::memcpy(s.data() + 4, &uncompressed, 4);
        return h + s;
    };
    const auto used = static_cast<uint32_t>(good.size() - 8);
    expect_error([&] { (void)read_pcd(with_sizes(used + 1, 1200), "c.pcd"); },
                 ErrorCode::kMalformedInput, "c.pcd: the compressed block says");
    expect_error([&] { (void)read_pcd(with_sizes(used, 1204), "c.pcd"); },
                 ErrorCode::kMalformedInput, "1204 bytes uncompressed but header says 100 points");
    expect_error([&] { (void)read_pcd(h + "\x10\0\0", "c.pcd"); }, ErrorCode::kMalformedInput,
                 "lacks its two size words");
    // The right sizes around a damaged stream.
    std::string corrupt = h + good;
    for (std::size_t i = h.size() + 8; i < corrupt.size(); i += 3) corrupt[i] = '\xff';
    expect_error([&] { (void)read_pcd(corrupt, "c.pcd"); }, ErrorCode::kMalformedInput,
                 "does not decompress");
    // More than LZF could ever expand to, refused before allocating.
    const std::string huge =
        header("x y z", "4 4 4", "F F F", "1 1 1", 300000000, 1, "binary_compressed");
    std::string tiny;
    append_little_endian<uint32_t>(tiny, 4);
    append_little_endian<uint32_t>(tiny, 3600000000u);
    tiny += "abcd";
    expect_error([&] { (void)read_pcd(huge + tiny, "c.pcd"); }, ErrorCode::kMalformedInput,
                 "cannot hold 3600000000 bytes");
}

// ---- normals ---------------------------------------------------------------------------------

TEST(Pcd, NormalsAndLabelsRoundTripBitForBitInEveryDataKind) {
    PointCloud cloud = sample_cloud(400, 71, true, true);
    add_normals(cloud, 72);
    for (PcdEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = pcd_of(cloud, enc);
        EXPECT_NE(bytes.find("FIELDS x y z normal_x normal_y normal_z label\nSIZE 4 4 4 4 4 4 4\n"
                             "TYPE F F F F F F I\nCOUNT 1 1 1 1 1 1 1\n"),
                  std::string::npos);
        const PointCloud back = read_pcd(bytes, "n.pcd");
        expect_same_cloud(cloud, back, 0.0);
        expect_same_normals(cloud, back);
    }
}

TEST(Pcd, NormalsStayF4BesideF8Coordinates) {
    PointCloud cloud = georeferenced_cloud(300, 73);
    add_normals(cloud, 74);
    for (PcdEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = pcd_of(cloud, enc);
        EXPECT_NE(bytes.find("FIELDS x y z normal_x normal_y normal_z\nSIZE 8 8 8 4 4 4\n"
                             "TYPE F F F F F F\n"),
                  std::string::npos);
        const PointCloud back = read_pcd(bytes, "geo.pcd");
        expect_same_cloud(cloud, back, 1e-5);
        expect_same_normals(cloud, back);
    }
}

TEST(Pcd, WriteNormalsFalseWritesTheBytesOfACloudWithoutNormals) {
    const PointCloud plain = sample_cloud(60, 75, true, true);
    PointCloud with = plain;
    add_normals(with, 76);
    io::ReadOptions off;
    off.read_normals = false;
    for (PcdEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string left_out =
            written([&](std::ostream& o) { write_pcd(o, with, enc, true, false); });
        EXPECT_EQ(left_out, pcd_of(plain, enc));
        EXPECT_TRUE(read_pcd(left_out, "n.pcd").normals.empty());
        // A file with normals read without them: the same points and labels.
        const PointCloud back = read_pcd(pcd_of(with, enc), "n.pcd", off);
        EXPECT_TRUE(back.normals.empty());
        expect_same_cloud(plain, back, 0.0);
    }
}

TEST(Pcd, NormalsOfTheWrongCountAreRefusedBeforeWriting) {
    PointCloud cloud = sample_cloud(10, 77, false, true);
    cloud.normals.assign(11, Vec3f(0, 0, 1));
    for (PcdEncoding enc : kAllEncodings) {
        for (bool write_normals : {true, false}) {
            std::ostringstream out;
            expect_error([&] { write_pcd(out, cloud, enc, true, write_normals); },
                         ErrorCode::kInvalidParameter, "the cloud has 11 normals for 10 points");
            EXPECT_TRUE(out.str().empty());
        }
    }
}

// pcl::PointNormal as PCL lays it out: padding after x y z and after the normal, curvature.
TEST(Pcd, ReadsPclPointNormalInEveryDataKind) {
    const std::string fields = "x y z _ normal_x normal_y normal_z _ curvature _";
    const std::string sizes = "4 4 4 1 4 4 4 1 4 1";
    const std::string types = "F F F U F F F U F U";
    const std::string counts = "1 1 1 4 1 1 1 4 1 12";
    const float xyz[2][3] = {{1, 2, 3}, {-4, 5.5f, 6}};
    const float nrm[2][3] = {{0.6f, 0, -0.8f}, {0, -1, 0}};
    std::string raw, soa;
    for (int i = 0; i < 2; ++i) {
        for (float v : xyz[i]) append_little_endian(raw, v);
        raw.append(4, '\0');
        for (float v : nrm[i]) append_little_endian(raw, v);
        raw.append(4, '\0');
        append_little_endian(raw, 0.01f);
        raw.append(12, '\0');
    }
    for (int a = 0; a < 3; ++a) {
        for (int i = 0; i < 2; ++i) append_little_endian(soa, xyz[i][a]);
    }
    for (int a = 0; a < 3; ++a) {
        for (int i = 0; i < 2; ++i) append_little_endian(soa, nrm[i][a]);
    }
    for (int i = 0; i < 2; ++i) append_little_endian(soa, 0.01f);
    const std::string pad4 = "0 0 0 0", pad12 = "0 0 0 0 0 0 0 0 0 0 0 0";
    const std::string ascii = "1 2 3 " + pad4 + " 0.6 0 -0.8 " + pad4 + " 0.01 " + pad12 +
                              "\n-4 5.5 6 " + pad4 + " 0 -1 0 " + pad4 + " 0.01 " + pad12 + "\n";
    const std::string files[] = {
        header(fields, sizes, types, counts, 2, 1, "ascii") + ascii,
        header(fields, sizes, types, counts, 2, 1, "binary") + raw,
        header(fields, sizes, types, counts, 2, 1, "binary_compressed") + lzf_block(soa),
    };
    for (const std::string& f : files) {
        const PointCloud c = read_pcd(f, "pn.pcd");
        EXPECT_EQ(c.points, (std::vector<Vec3f>{{1, 2, 3}, {-4, 5.5f, 6}}));
        EXPECT_EQ(c.normals, (std::vector<Vec3f>{{0.6f, 0, -0.8f}, {0, -1, 0}}));
    }
}

TEST(Pcd, ReadsNormalsOfAnyTypeOnlyWhenAllThreeAreUsable) {
    // F8 and I2 normals, in another order than x y z.
    std::string bin = header("normal_z x y z normal_x normal_y", "2 4 4 4 8 1", "I F F F F I",
                             "1 1 1 1 1 1", 1, 1, "binary");
    append_little_endian<int16_t>(bin, -2);
    for (float v : {1.0f, 2.0f, 3.0f}) append_little_endian(bin, v);
    append_little_endian(bin, 0.5);
    append_little_endian<int8_t>(bin, 7);
    const PointCloud c = read_pcd(bin, "t.pcd");
    EXPECT_EQ(c.points.at(0), Vec3f(1, 2, 3));
    EXPECT_EQ(c.normals, (std::vector<Vec3f>{{0.5f, 7, -2}}));

    // Two of three, or one with COUNT 3: read without normals, as before.
    const std::string two =
        header("x y z normal_x normal_y", "4 4 4 4 4", "F F F F F", "1 1 1 1 1", 1, 1, "ascii") +
        "1 2 3 0 1\n";
    EXPECT_TRUE(read_pcd(two, "two.pcd").normals.empty());
    const std::string counted = header("x y z normal_x normal_y normal_z", "4 4 4 4 4 4",
                                       "F F F F F F", "1 1 1 3 1 1", 1, 1, "ascii") +
                                "1 2 3 0 0 0 1 0\n";
    const PointCloud k = read_pcd(counted, "count.pcd");
    EXPECT_TRUE(k.normals.empty());
    EXPECT_EQ(k.points.at(0), Vec3f(1, 2, 3));

    // A normal that is not a number is malformed, unless normals are switched off.
    const std::string bad = header("x y z normal_x normal_y normal_z", "4 4 4 4 4 4", "F F F F F F",
                                   "1 1 1 1 1 1", 1, 1, "ascii") +
                            "1 2 3 0 zero 1\n";
    expect_error([&] { (void)read_pcd(bad, "bad.pcd"); }, ErrorCode::kMalformedInput,
                 "bad.pcd line 12: normal_y 'zero' is not a number");
    io::ReadOptions off;
    off.read_normals = false;
    EXPECT_EQ(read_pcd(bad, "bad.pcd", off).points.at(0), Vec3f(1, 2, 3));
}

}  // namespace
}  // namespace surfgrow::test
