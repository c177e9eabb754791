// Bad input never crashes and never makes the readers allocate from the file's claims:
// truncated files, corrupted bytes, and headers with absurd counts.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "io_test_helpers.hpp"
#include "surfgrow/io/ascii_scan.hpp"
#include "surfgrow/io/cloud_io.hpp"
#include "surfgrow/io/pcd.hpp"
#include "surfgrow/io/ply.hpp"
#include "surfgrow/io/text_cloud.hpp"

// The largest single allocation, to show that hostile headers are refused before allocating.
// GCC cannot tell that these replacements pair malloc with free consistently.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
std::size_t g_largest_allocation = 0;
}

void* operator new(std::size_t size) {
    if (size > g_largest_allocation) g_largest_allocation = size;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
    return operator new(size);
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}

namespace surfgrow::test {
namespace {

using io::CloudFormat;

struct Sample {
    std::string name;
    CloudFormat format;
    bool ascii;
    std::string bytes;
};

std::vector<Sample> valid_samples() {
    const PointCloud cloud = sample_cloud(12, 41, true, true);
    const PointCloud geo = georeferenced_cloud(6, 42);
    PointCloud normals = sample_cloud(8, 44, true, true);
    add_normals(normals, 45);
    std::vector<Sample> out;
    for (auto enc : {io::PlyEncoding::kAscii, io::PlyEncoding::kBinaryLittleEndian,
                     io::PlyEncoding::kBinaryBigEndian}) {
        const bool ascii = enc == io::PlyEncoding::kAscii;
        const std::string e(io::to_string(enc));
        out.push_back({"labels_" + e + ".ply", CloudFormat::kPly, ascii,
                       written([&](std::ostream& o) { io::write_ply(o, cloud, enc); })});
        out.push_back({"geo_" + e + ".ply", CloudFormat::kPly, ascii,
                       written([&](std::ostream& o) { io::write_ply(o, geo, enc); })});
        out.push_back({"normals_" + e + ".ply", CloudFormat::kPly, ascii,
                       written([&](std::ostream& o) { io::write_ply(o, normals, enc); })});
    }
    // Faces after the vertices: a cut inside them must be noticed too.
    std::string mesh = written([&](std::ostream& o) {
        io::write_ply(o, cloud, io::PlyEncoding::kBinaryLittleEndian, false);
    });
    mesh.replace(mesh.find("end_header\n"), 11,
                 "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
    for (int f = 0; f < 2; ++f) {
        append_little_endian<uint8_t>(mesh, 3);
        for (int32_t v : {0, 1, 2}) append_little_endian(mesh, v);
    }
    out.push_back({"mesh.ply", CloudFormat::kPly, false, mesh});
    for (auto enc :
         {io::PcdEncoding::kAscii, io::PcdEncoding::kBinary, io::PcdEncoding::kBinaryCompressed}) {
        const std::string e(io::to_string(enc));
        const bool ascii = enc == io::PcdEncoding::kAscii;
        out.push_back({"labels_" + e + ".pcd", CloudFormat::kPcd, ascii,
                       written([&](std::ostream& o) { io::write_pcd(o, cloud, enc); })});
        out.push_back({"geo_" + e + ".pcd", CloudFormat::kPcd, ascii,
                       written([&](std::ostream& o) { io::write_pcd(o, geo, enc); })});
        out.push_back({"normals_" + e + ".pcd", CloudFormat::kPcd, ascii,
                       written([&](std::ostream& o) { io::write_pcd(o, normals, enc); })});
    }
    out.push_back({"labels.xyz", CloudFormat::kText, true,
                   written([&](std::ostream& o) { io::write_text_cloud(o, cloud, ' ', true); })});
    out.push_back({"normals.csv", CloudFormat::kText, true,
                   written([&](std::ostream& o) { io::write_text_cloud(o, normals, ',', true); })});
    return out;
}

// With SURFGROW_FUZZ_SEEDS=<folder> set, every sample is also written to
// <folder>/read_cloud_<ply|pcd|text>/<name>: the seeds of the fuzzers (docs/fuzzing.md).
void dump_seed(CloudFormat format, const std::string& name, const std::string& bytes) {
    const char* root = std::getenv("SURFGROW_FUZZ_SEEDS");
    if (root == nullptr) return;
    const char* target = format == CloudFormat::kPly   ? "read_cloud_ply"
                         : format == CloudFormat::kPcd ? "read_cloud_pcd"
                                                       : "read_cloud_text";
    const std::filesystem::path dir = std::filesystem::path(root) / target;
    std::filesystem::create_directories(dir);
    std::ofstream(dir / name, std::ios::binary) << bytes;
}

// Offset of the first byte of the last value in an ASCII file: a prefix that reaches it holds
// every value (the last one possibly cut short, which no reader can notice).
std::size_t last_value_start(const std::string& bytes) {
    std::size_t end = bytes.size();
    while (end > 0 && is_blank(bytes[end - 1])) --end;
    std::size_t start = end;
    while (start > 0 && !is_blank(bytes[start - 1])) --start;
    return start;
}

TEST(HostileInput, EveryTruncationIsMalformedUnlessTheFileIsComplete) {
    for (const Sample& s : valid_samples()) {
        SCOPED_TRACE(s.name);
        dump_seed(s.format, s.name, s.bytes);
        const PointCloud full = io::read_cloud(s.bytes, s.format, s.name);
        const std::size_t complete = s.ascii ? last_value_start(s.bytes) + 1 : s.bytes.size();
        for (std::size_t len = 0; len < s.bytes.size(); ++len) {
            const std::string prefix = s.bytes.substr(0, len);
            try {
                const PointCloud c = io::read_cloud(prefix, s.format, s.name);
                if (s.format == CloudFormat::kText) {
                    // A text file cut between rows is a shorter valid file.
                    ASSERT_LE(c.size(), full.size()) << len;
                } else {
                    ASSERT_GE(len, complete) << "a truncated file was accepted";
                    ASSERT_EQ(c.size(), full.size()) << len;
                }
            } catch (const Error& e) {
                ASSERT_EQ(e.code(), ErrorCode::kMalformedInput) << len << ": " << e.what();
                ASSERT_NE(std::string(e.what()).find(s.name), std::string::npos) << e.what();
            }
        }
    }
}

TEST(HostileInput, CorruptedBytesNeverCrash) {
    std::mt19937_64 rng(43);
    for (const Sample& s : valid_samples()) {
        SCOPED_TRACE(s.name);
        for (int trial = 0; trial < 300; ++trial) {
            std::string bytes = s.bytes;
            const int flips = 1 + static_cast<int>(rng() % 4);
            for (int k = 0; k < flips; ++k) {
                bytes[rng() % bytes.size()] = static_cast<char>(rng() & 0xff);
            }
            try {
                (void)io::read_cloud(bytes, s.format, s.name);
            } catch (const Error& e) {
                ASSERT_EQ(e.code(), ErrorCode::kMalformedInput) << e.what();
            }
        }
    }
}

// Headers that claim far more than the file holds fail fast, without allocating for the claim.
TEST(HostileInput, AbsurdHeadersFailWithoutLargeAllocations) {
    const std::string xyz_f = "property float x\nproperty float y\nproperty float z\n";
    const std::string pcd_tail = "SIZE 4 4 4\nTYPE F F F\n";
    const struct {
        std::string name;
        CloudFormat format;
        std::string bytes;
    } cases[] = {
        {"huge_vertices.ply", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\n" + xyz_f +
             "end_header\n" + std::string(24, '\0')},
        {"overflow_vertices.ply", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement vertex 18446744073709551615\n" + xyz_f +
             "end_header\n"},
        {"too_big_count.ply", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\n" + xyz_f +
             "end_header\n"},
        {"huge_ascii.ply", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 1000000000\n" + xyz_f + "end_header\n1 2 3\n"},
        {"huge_faces_first.ply", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement face 1000000000000000000\n"
         "property list uchar int idx\nelement vertex 1\n" +
             xyz_f + "end_header\n\x03"},
        {"huge_list.ply", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint int idx\n"
         "element vertex 0\n" +
             xyz_f + "end_header\n\xff\xff\xff\xff"},
        {"huge_points.pcd", CloudFormat::kPcd,
         "FIELDS x y z\n" + pcd_tail + "POINTS 1000000000000000\nDATA binary\n" +
             std::string(12, '\0')},
        {"huge_ascii.pcd", CloudFormat::kPcd,
         "FIELDS x y z\n" + pcd_tail + "POINTS 1000000000\nDATA ascii\n1 2 3\n"},
        {"huge_wh.pcd", CloudFormat::kPcd,
         "FIELDS x y z\n" + pcd_tail + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA binary\n"},
        {"absurd_count.pcd", CloudFormat::kPcd,
         "FIELDS x y z pad\nSIZE 4 4 4 8\nTYPE F F F F\nCOUNT 1 1 1 4000000000000000000\n"
         "POINTS 2\nDATA binary\n" +
             std::string(64, '\0')},
        {"absurd_count.pcd", CloudFormat::kPcd,
         "FIELDS x y z pad\nSIZE 4 4 4 8\nTYPE F F F F\nCOUNT 1 1 1 4000000000000000000\n"
         "POINTS 2\nDATA ascii\n1 2 3 4\n"},
        {"negative.pcd", CloudFormat::kPcd,
         "FIELDS x y z\nSIZE 4 4 -4\nTYPE F F F\nPOINTS 1\nDATA binary\n" + std::string(12, '\0')},
        {"lzf_lies.pcd", CloudFormat::kPcd,
         "FIELDS x y z\n" + pcd_tail + "POINTS 300000000\nDATA binary_compressed\n" +
             std::string("\x04\0\0\0\x00\x8c\x93\xd6"
                         "abcd",
                         12)},
        {"long_header_line.pcd", CloudFormat::kPcd, "FIELDS" + std::string(200000, ' ') + "x\n"},
        {"long_header_line.ply", CloudFormat::kPly,
         "ply\ncomment " + std::string(200000, 'a') + "\n"},
        {"wide_row.xyz", CloudFormat::kText, std::string(200000, '1') + "\n"},
        {"huge_normals.ply", CloudFormat::kPly,
         "ply\nformat ascii 1.0\nelement vertex 1000000000\n" + xyz_f +
             "property float nx\nproperty float ny\nproperty list uchar int idx\n"
             "property double nz\nend_header\n1 2 3 0 0 0 1\n"},
        {"huge_normals_bin.ply", CloudFormat::kPly,
         "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n" + xyz_f +
             "property list uchar int idx\nproperty float nx\nproperty float ny\n"
             "property float nz\nend_header\n" +
             std::string(30, '\0')},
        {"huge_normals.pcd", CloudFormat::kPcd,
         "FIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\n"
         "POINTS 1000000000\nDATA ascii\n1 2 3 0 0 1\n"},
        {"huge_normals_bin.pcd", CloudFormat::kPcd,
         "FIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\n"
         "POINTS 1000000000\nDATA binary\n" +
             std::string(24, '\0')},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        dump_seed(c.format, "absurd_" + c.name, c.bytes);
        g_largest_allocation = 0;
        expect_error([&] { (void)io::read_cloud(c.bytes, c.format, c.name); },
                     ErrorCode::kMalformedInput, c.name);
        // The file itself is at most 200 kB; nothing allocated may be much larger than that.
        EXPECT_LT(g_largest_allocation, std::size_t{1} << 20);
    }
    // Elements without properties take no bytes, so any count of them is valid (and cheap).
    for (const char* enc : {"ascii", "binary_little_endian"}) {
        SCOPED_TRACE(enc);
        std::string ply = std::string("ply\nformat ") + enc +
                          " 1.0\nelement nothing 18446744073709551615\nelement vertex 1\n" + xyz_f +
                          "end_header\n";
        if (enc[0] == 'a') {
            ply += "1 2 3\n";
        } else {
            for (float v : {1.0f, 2.0f, 3.0f}) append_little_endian(ply, v);
        }
        EXPECT_EQ(io::read_cloud(ply, CloudFormat::kPly, "empty.ply").points.at(0), Vec3f(1, 2, 3));
    }
}

}  // namespace
}  // namespace surfgrow::test
