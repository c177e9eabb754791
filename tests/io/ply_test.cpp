// PLY: every encoding, scalar type and element layout the reader must handle, and its errors.
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "io_test_helpers.hpp"
#include "surfgrow/io/ply.hpp"

namespace surfgrow::test {
namespace {

using io::PlyEncoding;
using io::read_ply;
using io::write_ply;

constexpr PlyEncoding kAllEncodings[] = {PlyEncoding::kAscii, PlyEncoding::kBinaryLittleEndian,
                                         PlyEncoding::kBinaryBigEndian};

std::string ply_of(const PointCloud& cloud, PlyEncoding enc, bool labels = true) {
    return written([&](std::ostream& out) { write_ply(out, cloud, enc, labels); });
}

TEST(Ply, RoundTripsEveryEncodingWithLabelsAndNaNInPlace) {
    const PointCloud cloud = sample_cloud(500, 1, true, true);
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const PointCloud back = read_ply(ply_of(cloud, enc), "mem.ply");
        expect_same_cloud(cloud, back, 0.0);
        EXPECT_EQ(back.offset, Vec3d::Zero());
        EXPECT_TRUE(std::isnan(back.points[3].x()));
    }
}

TEST(Ply, WritesFloatCoordinatesWithoutOffsetAndDoubleWithIt) {
    const std::string plain = ply_of(sample_cloud(3, 2, false, false), PlyEncoding::kAscii);
    EXPECT_NE(plain.find("property float x\n"), std::string::npos);
    EXPECT_EQ(plain.find("label"), std::string::npos);
    const std::string geo = ply_of(georeferenced_cloud(3, 2), PlyEncoding::kAscii);
    EXPECT_NE(geo.find("property double x\n"), std::string::npos);
}

TEST(Ply, LargeDoubleCoordinatesSurviveThroughAnOffset) {
    const PointCloud cloud = georeferenced_cloud(1000, 3);
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const PointCloud back = read_ply(ply_of(cloud, enc), "geo.ply");
        // Stored floats stay small: within the +-50 m cloud around a rounded first point.
        EXPECT_NE(back.offset, Vec3d::Zero());
        for (const Vec3f& p : back.points) EXPECT_LT(p.cwiseAbs().maxCoeff(), 101.0f);
        // ~1e-12 relative to the 5.4e6 m coordinates, 1e-6 relative to the cloud's extent.
        expect_same_cloud(cloud, back, 1e-5);
    }
}

TEST(Ply, OffsetComesFromTheFirstLargeFinitePointRounded) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
        "property double z\nend_header\n"
        "nan nan nan\n1 2 3\n500000.4 5400000.6 -20000.5\n500001 5400001 -20000\n";
    const PointCloud c = read_ply(ply, "a.ply");
    EXPECT_EQ(c.offset, Vec3d(500000, 5400001, -20001));  // round(-20000.5) = -20001
    EXPECT_TRUE(std::isnan(c.points[0].x()));
    // The small point read before the offset was chosen is moved to it as well.
    EXPECT_NEAR(absolute(c, 1).x(), 1.0, 0.1);
    EXPECT_NEAR(c.points[2].x(), 0.4f, 1e-6f);
    EXPECT_NEAR(c.points[3].z(), 1.0f, 1e-6f);
}

TEST(Ply, SentinelsAndPartlyNaNPointsDoNotSetTheOffset) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
        "property double z\nend_header\n"
        "3.4e38 3.4e38 3.4e38\n20000 nan 0\ninf 1 1\n1.5 2.5 3.5\n";
    const PointCloud c = read_ply(ply, "s.ply");
    EXPECT_EQ(c.offset, Vec3d::Zero());
    EXPECT_EQ(c.points[0].x(), static_cast<float>(3.4e38));  // a sentinel, kept as it is
    EXPECT_EQ(c.points[1].x(), 20000.0f);
    EXPECT_EQ(c.points[3], Vec3f(1.5f, 2.5f, 3.5f));
}

TEST(Ply, SmallDoublesAndLargeFloatsKeepAZeroOffset) {
    const std::string small =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\n"
        "property double z\nend_header\n1.5 -2.25 9999\n";
    EXPECT_EQ(read_ply(small, "s.ply").offset, Vec3d::Zero());
    const std::string big_float =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n500000 5400000 300\n";
    const PointCloud c = read_ply(big_float, "f.ply");
    EXPECT_EQ(c.offset, Vec3d::Zero());
    EXPECT_EQ(c.points[0].y(), 5400000.0f);
}

// A binary_big_endian file written here, not by write_ply: double x y z between other
// properties, an int label, and a face element after the vertices.
TEST(Ply, ReadsBigEndianWrittenByAnotherWriter) {
    std::string ply =
        "ply\nformat binary_big_endian 1.0\ncomment from a test helper\nelement vertex 3\n"
        "property uchar red\nproperty double x\nproperty double y\nproperty double z\n"
        "property float nx\nproperty int label\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const double xyz[3][3] = {{1.5, -2.0, 3.25}, {600000.5, 5000000.25, 10.0}, {0, 0, 0}};
    for (int i = 0; i < 3; ++i) {
        append_big_endian<uint8_t>(ply, 200);
        for (int a = 0; a < 3; ++a) append_big_endian(ply, xyz[i][a]);
        append_big_endian(ply, 0.5f);
        append_big_endian<int32_t>(ply, 100 + i);
    }
    append_big_endian<uint8_t>(ply, 3);
    for (int32_t v : {0, 1, 2}) append_big_endian(ply, v);

    const PointCloud c = read_ply(ply, "be.ply");
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c.offset, Vec3d(600001, 5000000, 10));
    for (int i = 0; i < 3; ++i) {
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(absolute(c, i)[a], xyz[i][a], 1e-6) << i << " " << a;
        }
    }
    EXPECT_EQ(c.labels, (std::vector<int32_t>{100, 101, 102}));
}

TEST(Ply, ReadsEveryScalarTypeAndAlias) {
    const char* names[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                           "float", "double", "int8",    "uint8",  "int16", "uint16",
                           "int32", "uint32", "float32", "float64"};
    for (const char* name : names) {
        SCOPED_TRACE(name);
        const std::string header = std::string("ply\nformat ascii 1.0\nelement vertex 2\n") +
                                   "property " + name + " x\nproperty " + name + " y\nproperty " +
                                   name + " z\nend_header\n";
        const PointCloud c = read_ply(header + "1 2 3\n4 5 6\n", "t.ply");
        ASSERT_EQ(c.size(), 2u);
        EXPECT_EQ(c.points[1], Vec3f(4, 5, 6));
    }
    // Mixed widths in one binary record, including negative values and 64-bit integers.
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty short x\n"
        "property uint64 y\nproperty char z\nproperty ushort label\nend_header\n";
    append_little_endian<int16_t>(ply, -300);
    append_little_endian<uint64_t>(ply, 7);
    append_little_endian<int8_t>(ply, -5);
    append_little_endian<uint16_t>(ply, 65535);
    const PointCloud c = read_ply(ply, "mixed.ply");
    EXPECT_EQ(c.points[0], Vec3f(-300, 7, -5));
    EXPECT_EQ(c.labels, std::vector<int32_t>{65535});
}

// The same mesh in all three encodings: an element before the vertices, faces after them.
std::string mesh_ply(PlyEncoding enc) {
    std::string s = "ply\nformat " + std::string(io::to_string(enc)) +
                    " 1.0\nobj_info made by hand\nelement material 2\nproperty uchar r\n"
                    "property list ushort float samples\nelement vertex 3\nproperty float x\n"
                    "property float y\nproperty float z\nproperty list uchar uint idx\n"
                    "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
                    "element empty 0\nend_header\n";
    if (enc == PlyEncoding::kAscii) {
        return s +
               "1 2 0.5 0.25\n2 0\n"
               "1 2 3 1 7\n4 5 6 0\n7 8 9 3 1 2 3\n"
               "3 0 1 2 9\n4 0 1 2 0 9\n";
    }
    const bool be = enc == PlyEncoding::kBinaryBigEndian;
    auto put = [&](auto v) { be ? append_big_endian(s, v) : append_little_endian(s, v); };
    put(uint8_t{1}), put(uint16_t{2}), put(0.5f), put(0.25f);
    put(uint8_t{2}), put(uint16_t{0});
    const float v[3][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
    const uint8_t lists[3] = {1, 0, 3};
    for (int i = 0; i < 3; ++i) {
        for (float f : v[i]) put(f);
        put(lists[i]);
        for (uint8_t k = 0; k < lists[i]; ++k) put(uint32_t{k});
    }
    put(uint8_t{3}), put(0), put(1), put(2), put(uint8_t{9});
    put(uint8_t{4}), put(0), put(1), put(2), put(0), put(uint8_t{9});
    return s;
}

TEST(Ply, SkipsElementsBeforeAndAfterVerticesAndListsInEveryEncoding) {
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const PointCloud c = read_ply(mesh_ply(enc), "mesh.ply");
        ASSERT_EQ(c.size(), 3u);
        EXPECT_EQ(c.points[0], Vec3f(1, 2, 3));
        EXPECT_EQ(c.points[2], Vec3f(7, 8, 9));
        EXPECT_TRUE(c.labels.empty());
    }
}

TEST(Ply, HeaderWithCarriageReturnsCommentsAndBlankLines) {
    const std::string ply =
        "ply\r\nformat ascii 1.0\r\ncomment hello\r\n\r\nelement vertex 1\r\nproperty float x\r\n"
        "property float y\r\nproperty float z\r\nend_header\r\n1 2 3\r\n";
    EXPECT_EQ(read_ply(ply, "crlf.ply").points.at(0), Vec3f(1, 2, 3));
}

TEST(Ply, LabelFieldCanBeRenamedOrSwitchedOff) {
    const PointCloud cloud = sample_cloud(20, 4, false, true);
    const std::string ply = ply_of(cloud, PlyEncoding::kBinaryLittleEndian);
    io::ReadOptions off;
    off.read_labels = false;
    EXPECT_TRUE(read_ply(ply, "l.ply", off).labels.empty());
    io::ReadOptions other;
    other.label_field = "segment";
    EXPECT_TRUE(read_ply(ply, "l.ply", other).labels.empty());
    const std::string seg =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nproperty uint segment\nend_header\n0 0 0 4294967295\n1 1 1 12\n";
    EXPECT_EQ(read_ply(seg, "s.ply", other).labels, (std::vector<int32_t>{-1, 12}));
    EXPECT_FALSE(ply_of(cloud, PlyEncoding::kAscii, false).find("label") != std::string::npos);
}

TEST(Ply, EmptyCloudRoundTrips) {
    for (PlyEncoding enc : kAllEncodings) {
        EXPECT_TRUE(read_ply(ply_of(PointCloud{}, enc), "e.ply").empty());
    }
}

TEST(Ply, HeaderErrorsAreMalformedAndNameTheFile) {
    const std::string v = "element vertex 1\nproperty float x\nproperty float y\n";
    const std::string end = "property float z\nend_header\n1 2 3\n";
    const struct {
        std::string text;
        std::string needle;
    } cases[] = {
        {"", "empty"},
        {"plx\nformat ascii 1.0\n", "not a PLY file"},
        {"ply\n" + v + end, "no format line"},
        {"ply\nformat ascii 2.0 x\n" + v + end, "format"},
        {"ply\nformat utf8 1.0\n" + v + end, "unknown PLY encoding"},
        {"ply\nformat ascii 1.0\nproperty float x\n" + v + end, "before any element"},
        {"ply\nformat ascii 1.0\nelement vertex -1\n", "count"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\n", "unknown property type"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n", "list types"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nweird stuff\n", "unknown header keyword"},
        {"ply\nformat ascii 1.0\n" + v, "before end_header"},
        {"ply\nformat ascii 1.0\n" + v + "end_header\n1 2\n", "no z property"},
        {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", "no vertex element"},
        {"ply\nformat ascii 1.0\n" + v + "property float z\nelement vertex 0\n" +
             "property float x\nend_header\n1 2 3\n",
         "two vertex elements"},
        {"ply\nformat ascii 1.0\n" + v + "property list uchar float z\nend_header\n", "is a list"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string msg = expect_error([&] { (void)read_ply(c.text, "bad.ply"); },
                                             ErrorCode::kMalformedInput, c.needle);
        EXPECT_EQ(msg.rfind("bad.ply", 0), 0u) << msg;
    }
}

TEST(Ply, BodyErrorsSayWhatIsWrong) {
    const std::string h =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n";
    expect_error([&] { (void)read_ply(h + std::string(8000, '\1'), "cloud.ply"); },
                 ErrorCode::kMalformedInput,
                 "cloud.ply: header says 1000 vertices of 12 bytes but only 8000 bytes follow");

    const std::string a =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n";
    expect_error([&] { (void)read_ply(a + "1 2 3\n4 x 6\n", "n.ply"); }, ErrorCode::kMalformedInput,
                 "n.ply line 9: 'x' is not a number");
    expect_error([&] { (void)read_ply(a + "1 2 3\n4 5 6\n7\n", "long.ply"); },
                 ErrorCode::kMalformedInput, "long.ply line 10: more data after the last element");
    expect_error([&] { (void)read_ply(a + "1 2 3\n4 5\n", "short.ply"); },
                 ErrorCode::kMalformedInput, "the data ends inside vertex 1 of 2");
    expect_error([&] { (void)read_ply(a + "1 2 3\n4 5 6.5.5\n", "n2.ply"); },
                 ErrorCode::kMalformedInput, "'6.5.5' is not a number");

    // Binary: data after the last element, unless it is zero padding.
    const PointCloud cloud = sample_cloud(10, 5, false, false);
    const std::string bin = ply_of(cloud, PlyEncoding::kBinaryLittleEndian);
    EXPECT_EQ(read_ply(bin + std::string(16, '\0'), "pad.ply").size(), 10u);
    expect_error([&] { (void)read_ply(bin + "garbage", "tail.ply"); }, ErrorCode::kMalformedInput,
                 "tail.ply: 7 bytes follow the data the header declares");
    // A negative list length in a face.
    std::string faces =
        "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list char int idx\n"
        "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    append_little_endian<int8_t>(faces, -3);
    expect_error([&] { (void)read_ply(faces, "neg.ply"); }, ErrorCode::kMalformedInput,
                 "face 0 has a list of -3 items");
}

TEST(Ply, NonIntegerLabelsAreRejected) {
    const std::string a =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float label\nend_header\n1 2 3 4.5\n";
    expect_error([&] { (void)read_ply(a, "lab.ply"); }, ErrorCode::kMalformedInput,
                 "label 4.5 is not a 32-bit integer");
    const std::string b =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float label\nend_header\n1 2 3 4\n";
    EXPECT_EQ(read_ply(b, "lab.ply").labels, std::vector<int32_t>{4});
}

// ---- normals ---------------------------------------------------------------------------------

TEST(Ply, NormalsAndLabelsRoundTripBitForBitInEveryEncoding) {
    PointCloud cloud = sample_cloud(300, 51, true, true);
    add_normals(cloud, 52);
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = ply_of(cloud, enc);
        EXPECT_NE(bytes.find("property float z\nproperty float nx\nproperty float ny\n"
                             "property float nz\nproperty int label\nend_header\n"),
                  std::string::npos);
        const PointCloud back = read_ply(bytes, "n.ply");
        expect_same_cloud(cloud, back, 0.0);
        expect_same_normals(cloud, back);
    }
}

TEST(Ply, NormalsStayFloatBesideDoubleCoordinates) {
    PointCloud cloud = georeferenced_cloud(200, 53);
    add_normals(cloud, 54);
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string bytes = ply_of(cloud, enc);
        EXPECT_NE(bytes.find("property double z\nproperty float nx\n"), std::string::npos);
        const PointCloud back = read_ply(bytes, "geo.ply");
        expect_same_cloud(cloud, back, 1e-5);
        expect_same_normals(cloud, back);
    }
}

TEST(Ply, WriteNormalsFalseWritesTheBytesOfACloudWithoutNormals) {
    const PointCloud plain = sample_cloud(50, 55, true, true);
    PointCloud with = plain;
    add_normals(with, 56);
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const std::string left_out =
            written([&](std::ostream& o) { write_ply(o, with, enc, true, false, false); });
        EXPECT_EQ(left_out, ply_of(plain, enc));
        EXPECT_EQ(left_out.find("nx"), std::string::npos);
        EXPECT_TRUE(read_ply(left_out, "n.ply").normals.empty());
    }
}

TEST(Ply, ReadingWithoutNormalsGivesTheSamePointsAndLabels) {
    PointCloud cloud = sample_cloud(120, 57, true, true);
    add_normals(cloud, 58);
    io::ReadOptions off;
    off.read_normals = false;
    for (PlyEncoding enc : kAllEncodings) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const PointCloud back = read_ply(ply_of(cloud, enc), "n.ply", off);
        EXPECT_TRUE(back.normals.empty());
        expect_same_cloud(cloud, back, 0.0);
    }
}

TEST(Ply, NormalsOfTheWrongCountAreRefusedBeforeWriting) {
    PointCloud cloud = sample_cloud(10, 59, false, false);
    cloud.normals.assign(9, Vec3f(0, 0, 1));
    for (PlyEncoding enc : kAllEncodings) {
        for (bool write_normals : {true, false}) {
            std::ostringstream out;
            expect_error([&] { write_ply(out, cloud, enc, true, false, write_normals); },
                         ErrorCode::kInvalidParameter, "the cloud has 9 normals for 10 points");
            EXPECT_TRUE(out.str().empty());
        }
    }
}

TEST(Ply, ReadsNormalsOfAnyTypeWhenAllThreeAreThere) {
    // ASCII, double normals among other properties, not next to each other.
    const std::string a =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty double nz\n"
        "property float y\nproperty uchar red\nproperty double nx\nproperty float z\n"
        "property float ny\nend_header\n1 0.25 2 255 0.5 3 -0.75\n4 1 5 0 0 6 0\n";
    const PointCloud c = read_ply(a, "a.ply");
    EXPECT_EQ(c.points[0], Vec3f(1, 2, 3));
    ASSERT_EQ(c.normals.size(), 2u);
    EXPECT_EQ(c.normals[0], Vec3f(0.5f, -0.75f, 0.25f));
    EXPECT_EQ(c.normals[1], Vec3f(0, 0, 1));

    // Binary big-endian with short normals (quantised) and a char one.
    std::string b =
        "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty short nx\nproperty int16 ny\nproperty char nz\nend_header\n";
    for (float f : {1.0f, 2.0f, 3.0f}) append_big_endian(b, f);
    append_big_endian<int16_t>(b, -300);
    append_big_endian<int16_t>(b, 7);
    append_big_endian<int8_t>(b, -1);
    EXPECT_EQ(read_ply(b, "b.ply").normals, (std::vector<Vec3f>{{-300, 7, -1}}));

    // Only two of them, or one a list: no normals, the points as before.
    const std::string two =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nend_header\n1 2 3 0 1\n";
    EXPECT_TRUE(read_ply(two, "two.ply").normals.empty());
    EXPECT_EQ(read_ply(two, "two.ply").points[0], Vec3f(1, 2, 3));
    const std::string list =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty list uchar float nz\n"
        "end_header\n1 2 3 0 1 2 0.5 0.5\n";
    EXPECT_TRUE(read_ply(list, "list.ply").normals.empty());
    EXPECT_EQ(read_ply(list, "list.ply").points[0], Vec3f(1, 2, 3));
}

TEST(Ply, NormalsBesideListsInVerticesAreReadRecordByRecord) {
    for (PlyEncoding enc : {PlyEncoding::kBinaryLittleEndian, PlyEncoding::kBinaryBigEndian}) {
        SCOPED_TRACE(std::string(io::to_string(enc)));
        const bool be = enc == PlyEncoding::kBinaryBigEndian;
        std::string s = "ply\nformat " + std::string(io::to_string(enc)) +
                        " 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                        "property float z\nproperty list uchar int idx\nproperty double nx\n"
                        "property float ny\nproperty float nz\nend_header\n";
        auto put = [&](auto v) { be ? append_big_endian(s, v) : append_little_endian(s, v); };
        put(1.0f), put(2.0f), put(3.0f), put(uint8_t{2}), put(7), put(8);
        put(0.5), put(0.25f), put(-1.0f);
        put(4.0f), put(5.0f), put(6.0f), put(uint8_t{0});
        put(-0.0), put(1.0f), put(0.0f);
        const PointCloud c = read_ply(s, "lists.ply");
        EXPECT_EQ(c.points, (std::vector<Vec3f>{{1, 2, 3}, {4, 5, 6}}));
        ASSERT_EQ(c.normals.size(), 2u);
        EXPECT_EQ(c.normals[0], Vec3f(0.5f, 0.25f, -1.0f));
        EXPECT_TRUE(std::signbit(c.normals[1].x()));
        EXPECT_EQ(c.normals[1], Vec3f(0, 1, 0));
    }
}

TEST(Ply, NormalsCanBeSwitchedOffAndBadOnesAreMalformed) {
    PointCloud cloud = sample_cloud(20, 60, false, false);
    add_normals(cloud, 61);
    io::ReadOptions off;
    off.read_normals = false;
    EXPECT_TRUE(read_ply(ply_of(cloud, PlyEncoding::kAscii), "n.ply", off).normals.empty());
    const std::string a =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "end_header\n1 2 3 0 up 1\n";
    expect_error([&] { (void)read_ply(a, "bad.ply"); }, ErrorCode::kMalformedInput,
                 "bad.ply line 11: 'up' is not a number (vertex 0, property ny)");
    EXPECT_EQ(read_ply(a, "bad.ply", off).points.at(0), Vec3f(1, 2, 3));
}

}  // namespace
}  // namespace surfgrow::test
