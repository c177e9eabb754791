// read_cloud / write_cloud: format choice, files on disk, atomic writes, and open errors.
#include <filesystem>
#include <fstream>
#include <string>

#include "io_test_helpers.hpp"
#include "support/test_support.hpp"
#include "surfgrow/io/cloud_io.hpp"

namespace surfgrow::test {
namespace {

namespace fs = std::filesystem;
using io::CloudFormat;
using io::read_cloud;
using io::write_cloud;

TEST(CloudIo, FormatFromExtension) {
    EXPECT_EQ(io::format_from_extension("a/b.PLY"), CloudFormat::kPly);
    EXPECT_EQ(io::format_from_extension("b.pcd"), CloudFormat::kPcd);
    for (const char* t : {"c.xyz", "c.txt", "c.CSV", "c.pts"}) {
        EXPECT_EQ(io::format_from_extension(t), CloudFormat::kText) << t;
    }
    EXPECT_EQ(io::format_from_extension("c.las"), std::nullopt);
    EXPECT_EQ(io::format_from_extension("noext"), std::nullopt);
}

TEST(CloudIo, DetectFormatFromContent) {
    EXPECT_EQ(io::detect_format("ply\nformat ascii 1.0\n"), CloudFormat::kPly);
    EXPECT_EQ(io::detect_format("# .PCD v0.7 - Point Cloud Data\nVERSION 0.7\n"),
              CloudFormat::kPcd);
    EXPECT_EQ(io::detect_format("VERSION .7\nFIELDS x y z\n"), CloudFormat::kPcd);
    EXPECT_EQ(io::detect_format("1 2 3\n4 5 6\n"), CloudFormat::kText);
    EXPECT_EQ(io::detect_format("X,Y,Z\n1,2,3\n"), CloudFormat::kText);
    EXPECT_EQ(io::detect_format(std::string("\x89PNG\r\n\x1a\n\0\0", 10)), std::nullopt);
    EXPECT_EQ(io::detect_format("hello world\n"), std::nullopt);
}

TEST(CloudIo, WritesAndReadsEveryFormatAndEncodingThroughFiles) {
    TempDir dir;
    const PointCloud cloud = sample_cloud(200, 31, true, true);
    struct Case {
        std::string name;
        io::WriteOptions options;
    };
    std::vector<Case> cases;
    for (auto enc : {io::PlyEncoding::kAscii, io::PlyEncoding::kBinaryLittleEndian,
                     io::PlyEncoding::kBinaryBigEndian}) {
        io::WriteOptions o;
        o.ply_encoding = enc;
        cases.push_back({"c_" + std::string(io::to_string(enc)) + ".ply", o});
    }
    for (auto enc :
         {io::PcdEncoding::kAscii, io::PcdEncoding::kBinary, io::PcdEncoding::kBinaryCompressed}) {
        io::WriteOptions o;
        o.pcd_encoding = enc;
        cases.push_back({"c_" + std::string(io::to_string(enc)) + ".pcd", o});
    }
    for (const char* ext : {".xyz", ".txt", ".csv", ".pts"}) {
        io::WriteOptions o;
        o.text_labels = true;
        cases.push_back({std::string("c") + ext, o});
    }
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        write_cloud(dir / c.name, cloud, c.options);
        expect_same_cloud(cloud, read_cloud(dir / c.name), 0.0);
    }
    EXPECT_EQ(read_bytes(dir / "c.csv").rfind("x,y,z,label\n", 0), 0u);
    EXPECT_EQ(read_bytes(dir / "c.pts").rfind("200\nx y z label\n", 0), 0u);
    // Without text_labels the text writer writes x y z only.
    write_cloud(dir / "plain.xyz", cloud);
    EXPECT_TRUE(read_cloud(dir / "plain.xyz").labels.empty());
}

TEST(CloudIo, ExplicitFormatOverridesTheExtension) {
    TempDir dir;
    const PointCloud cloud = sample_cloud(10, 32, false, false);
    io::WriteOptions w;
    w.format = CloudFormat::kPcd;
    write_cloud(dir / "cloud.bin", cloud, w);
    io::ReadOptions r;
    r.format = CloudFormat::kPcd;
    expect_same_cloud(cloud, read_cloud(dir / "cloud.bin", r), 0.0);
    // Without it, the content tells.
    expect_same_cloud(cloud, read_cloud(dir / "cloud.bin"), 0.0);
}

TEST(CloudIo, OpenErrors) {
    TempDir dir;
    expect_error([&] { (void)read_cloud(dir / "missing.ply"); }, ErrorCode::kCannotOpen,
                 "missing.ply");
    fs::create_directory(dir / "folder.pcd");
    expect_error([&] { (void)read_cloud(dir / "folder.pcd"); }, ErrorCode::kCannotOpen,
                 "folder.pcd: it is a folder");
    write_bytes(dir / "empty.xyz", "");
    expect_error([&] { (void)read_cloud(dir / "empty.xyz"); }, ErrorCode::kMalformedInput,
                 "empty.xyz: the file is empty");
    write_bytes(dir / "garbage.bin", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    expect_error([&] { (void)read_cloud(dir / "garbage.bin"); }, ErrorCode::kUnknownFormat,
                 "garbage.bin: unknown format");
    write_bytes(dir / "garbage.ply", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    expect_error([&] { (void)read_cloud(dir / "garbage.ply"); }, ErrorCode::kMalformedInput,
                 "garbage.ply: not a PLY file");
    write_bytes(dir / "garbage.pcd",
                "\x7f"
                "ELF\x02\x01\x01");
    expect_error([&] { (void)read_cloud(dir / "garbage.pcd"); }, ErrorCode::kMalformedInput,
                 "garbage.pcd: not a PCD file");
    write_bytes(dir / "garbage.xyz",
                "\x7f"
                "ELF\x02\x01\x01\n");
    expect_error([&] { (void)read_cloud(dir / "garbage.xyz"); }, ErrorCode::kMalformedInput,
                 "garbage.xyz");
    write_bytes(dir / "lies.pcd", "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
    expect_error([&] { (void)read_cloud(dir / "lies.pcd"); }, ErrorCode::kMalformedInput,
                 "lies.pcd: the extension says PCD but the content is PLY");
}

TEST(CloudIo, UnreadableFileIsCannotOpen) {
    // Permissions do not stop root, but /proc/self/mem cannot be read at offset 0 by anyone.
    if (!fs::exists("/proc/self/mem")) GTEST_SKIP() << "no /proc";
    expect_error([&] { (void)read_cloud("/proc/self/mem", {CloudFormat::kPly}); },
                 ErrorCode::kCannotOpen, "/proc/self/mem");
    TempDir dir;
    write_bytes(dir / "locked.ply", "ply\n");
    fs::permissions(dir / "locked.ply", fs::perms::none);
    if (std::ifstream(dir / "locked.ply").good()) GTEST_SKIP() << "running as root";
    expect_error([&] { (void)read_cloud(dir / "locked.ply"); }, ErrorCode::kCannotOpen,
                 "locked.ply: permission denied");
}

TEST(CloudIo, WriteErrorsLeaveThePreviousFile) {
    TempDir dir;
    const PointCloud cloud = sample_cloud(10, 33, false, false);
    expect_error([&] { write_cloud(dir / "out.las", cloud); }, ErrorCode::kUnknownFormat,
                 "out.las");
    EXPECT_FALSE(fs::exists(dir / "out.las"));
    write_cloud(dir / "keep.ply", cloud);
    const std::string before = read_bytes(dir / "keep.ply");
    PointCloud bad = cloud;
    bad.labels = {1, 2};  // not one per point: a bug in the caller
    expect_error([&] { write_cloud(dir / "keep.ply", bad); }, ErrorCode::kInternal, "2 labels");
    EXPECT_EQ(read_bytes(dir / "keep.ply"), before);
    expect_error([&] { write_cloud(dir / "no" / "such" / "dir.ply", cloud); },
                 ErrorCode::kCannotWrite, "dir.ply");
    // Only the final file is left in the folder: no temporaries.
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 1u);
}

TEST(CloudIo, NormalsRoundTripThroughEveryFormatAndEncoding) {
    TempDir dir;
    PointCloud cloud = sample_cloud(150, 34, true, true);
    add_normals(cloud, 35);
    struct Case {
        std::string name;
        io::WriteOptions options;
    };
    std::vector<Case> cases;
    for (auto enc : {io::PlyEncoding::kAscii, io::PlyEncoding::kBinaryLittleEndian,
                     io::PlyEncoding::kBinaryBigEndian}) {
        io::WriteOptions o;
        o.ply_encoding = enc;
        cases.push_back({"n_" + std::string(io::to_string(enc)) + ".ply", o});
    }
    for (auto enc :
         {io::PcdEncoding::kAscii, io::PcdEncoding::kBinary, io::PcdEncoding::kBinaryCompressed}) {
        io::WriteOptions o;
        o.pcd_encoding = enc;
        cases.push_back({"n_" + std::string(io::to_string(enc)) + ".pcd", o});
    }
    for (const char* ext : {".xyz", ".txt", ".csv", ".pts"}) {
        io::WriteOptions o;
        o.text_labels = true;
        cases.push_back({std::string("n") + ext, o});
    }
    io::ReadOptions without;
    without.read_normals = false;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        write_cloud(dir / c.name, cloud, c.options);
        const PointCloud back = read_cloud(dir / c.name);
        expect_same_cloud(cloud, back, 0.0);
        expect_same_normals(cloud, back);
        // Read as before normals were read: the same points and labels.
        const PointCloud old = read_cloud(dir / c.name, without);
        EXPECT_TRUE(old.normals.empty());
        expect_same_cloud(cloud, old, 0.0);
        // Left out on request: the file of the cloud without normals.
        io::WriteOptions no = c.options;
        no.write_normals = false;
        PointCloud plain = cloud;
        plain.normals.clear();
        write_cloud(dir / ("no_" + c.name), cloud, no);
        write_cloud(dir / ("plain_" + c.name), plain, c.options);
        EXPECT_EQ(read_bytes(dir / ("no_" + c.name)), read_bytes(dir / ("plain_" + c.name)));
    }
    EXPECT_EQ(read_bytes(dir / "n.csv").rfind("x,y,z,nx,ny,nz,label\n", 0), 0u);
    EXPECT_EQ(read_bytes(dir / "n.pts").rfind("150\nx y z nx ny nz label\n", 0), 0u);
}

TEST(CloudIo, NormalsOfTheWrongCountLeaveThePreviousFileAndNoTemporary) {
    TempDir dir;
    PointCloud cloud = sample_cloud(10, 36, false, false);
    write_cloud(dir / "keep.pcd", cloud);
    const std::string before = read_bytes(dir / "keep.pcd");
    cloud.normals.assign(3, Vec3f(0, 0, 1));
    for (bool write_normals : {true, false}) {
        io::WriteOptions o;
        o.write_normals = write_normals;
        for (const char* name : {"keep.pcd", "new.ply", "new.xyz"}) {
            expect_error([&] { write_cloud(dir / name, cloud, o); }, ErrorCode::kInvalidParameter,
                         "the cloud has 3 normals for 10 points");
        }
    }
    EXPECT_EQ(read_bytes(dir / "keep.pcd"), before);
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 1u);
}

}  // namespace
}  // namespace surfgrow::test
