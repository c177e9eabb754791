// The SIMD kernels chosen at run time: every instruction-set path gives the same bytes as the
// baseline one (kernel by kernel, and for a whole grown scan), and the baseline is right against
// brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "surfgrow/core/detail/simd_kernels.hpp"
#include "surfgrow/core/surface_grower.hpp"
#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"

using namespace surfgrow;
using detail::IndexRun;
using detail::KernelTable;
using detail::PointArrays;

namespace {

// Points in a 40 mm cube around the origin, padded like a cube index; labels in [0, 4).
struct Arrays {
    std::vector<float> x, y, z;
    std::vector<std::int32_t> labels;
    explicit Arrays(std::size_t n) {
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(-0.02f, 0.02f);
        const std::size_t padded = n + 64;
        x.resize(padded, 1e3f);
        y.resize(padded, 1e3f);
        z.resize(padded, 1e3f);
        labels.resize(padded, 0);
        for (std::size_t i = 0; i < n; ++i) {
            x[i] = u(rng);
            y[i] = u(rng);
            z[i] = 0.2f * u(rng);
            labels[i] = static_cast<std::int32_t>(rng() % 4);
        }
    }
    PointArrays view() const { return {x.data(), y.data(), z.data()}; }
};

// Runs of odd lengths and offsets, so that the masked tails are exercised.
const std::vector<IndexRun> kRuns = {{0, 3}, {5, 29}, {40, 41}, {57, 250}, {300, 300}, {301, 1000}};

const float kHome[3] = {0.001f, -0.002f, 0.0005f};
const float kNormal[3] = {0.0f, 0.6f, 0.8f};

std::vector<const KernelTable*> wider_tables() {
    std::vector<const KernelTable*> out;
    for (const char* isa : {"avx2", "avx512"})
        if (const KernelTable* t = detail::kernels_for(isa)) out.push_back(t);
    return out;
}

std::vector<std::uint32_t> within_all(const KernelTable& k, const Arrays& a, const float* p,
                                      float r2, const std::int32_t* labels) {
    std::vector<std::uint32_t> out;
    std::uint32_t buf[detail::kKernelChunk];
    for (const IndexRun& run : kRuns)
        for (std::uint32_t b = run.begin; b < run.end; b += detail::kKernelChunk) {
            const std::uint32_t e = std::min(run.end, b + detail::kKernelChunk);
            const IndexRun piece{b, e};
            const std::uint32_t n = k.within(a.view(), &piece, 1, p, r2, labels, 2, buf);
            out.insert(out.end(), buf, buf + n);
        }
    return out;
}

}  // namespace

TEST(SimdKernels, BaselineMatchesBruteForce) {
    const Arrays a(1000);
    const KernelTable& k = *detail::kernels_for("baseline");
    const float r = 0.012f;
    std::vector<std::uint32_t> expect, expect_other;
    double n = 0, sx = 0, szz = 0;
    for (const IndexRun& run : kRuns)
        for (std::uint32_t i = run.begin; i < run.end; ++i) {
            const float dx = a.x[i] - kHome[0], dy = a.y[i] - kHome[1], dz = a.z[i] - kHome[2];
            if (dx * dx + dy * dy + dz * dz > r * r) continue;
            expect.push_back(i);
            if (a.labels[i] != 2) expect_other.push_back(i);
            n += 1;
            sx += static_cast<double>(dx);
            szz += static_cast<double>(dz) * static_cast<double>(dz);
        }
    ASSERT_GT(expect.size(), 50u);
    EXPECT_EQ(within_all(k, a, kHome, r * r, nullptr), expect);
    EXPECT_EQ(within_all(k, a, kHome, r * r, a.labels.data()), expect_other);
    const detail::RawMoments m = k.moments(a.view(), kRuns.data(), kRuns.size(), kHome, r * r);
    EXPECT_EQ(m.v[0], n);
    EXPECT_NEAR(m.v[1], sx, 1e-6);
    EXPECT_NEAR(m.v[9], szz, 1e-8);
}

TEST(SimdKernels, EveryPathGivesTheBaselineBytes) {
    const auto wider = wider_tables();
    if (wider.empty()) GTEST_SKIP() << "this CPU or build has only the baseline kernels";
    const Arrays a(1000);
    const KernelTable& base = *detail::kernels_for("baseline");
    const float r2 = 0.015f * 0.015f;
    const float c[3] = {0.0f, 0.001f, 0.0f}, u[3] = {1, 0, 0}, v[3] = {0, 0.8f, -0.6f};
    for (const KernelTable* t : wider) {
        SCOPED_TRACE(t->isa);
        const detail::RawMoments m0 = base.moments(a.view(), kRuns.data(), kRuns.size(), kHome, r2);
        const detail::RawMoments m1 = t->moments(a.view(), kRuns.data(), kRuns.size(), kHome, r2);
        EXPECT_EQ(std::memcmp(&m0, &m1, sizeof m0), 0);
        const detail::FrameSums f0 = base.frame_sums(a.view(), kRuns.data(), kRuns.size(), kHome,
                                                     r2, c, u, v, kNormal, 0.004f);
        const detail::FrameSums f1 = t->frame_sums(a.view(), kRuns.data(), kRuns.size(), kHome, r2,
                                                   c, u, v, kNormal, 0.004f);
        EXPECT_EQ(std::memcmp(&f0, &f1, sizeof f0), 0);
        EXPECT_EQ(within_all(base, a, kHome, r2, a.labels.data()),
                  within_all(*t, a, kHome, r2, a.labels.data()));
        std::uint32_t i0[detail::kKernelChunk], i1[detail::kKernelChunk];
        float d0[detail::kKernelChunk], d1[detail::kKernelChunk];
        const IndexRun pieces[2] = {{57, 150}, {170, 250}};  // two runs in one call
        const std::uint32_t n0 =
            base.on_plane(a.view(), pieces, 2, kHome, r2, kNormal, 0.0005f, 0.003f, i0, d0);
        const std::uint32_t n1 =
            t->on_plane(a.view(), pieces, 2, kHome, r2, kNormal, 0.0005f, 0.003f, i1, d1);
        ASSERT_EQ(n0, n1);
        ASSERT_GT(n0, 0u);
        EXPECT_EQ(std::memcmp(i0, i1, n0 * sizeof *i0), 0);
        EXPECT_EQ(std::memcmp(d0, d1, n0 * sizeof *d0), 0);
    }
}

// The whole grower on two fused scans, once per path: labels and surfaces byte for byte.
TEST(SimdKernels, AGrownScanIsTheSameOnEveryPath) {
    const auto wider = wider_tables();
    if (wider.empty()) GTEST_SKIP() << "this CPU or build has only the baseline kernels";
    const scanner::Scene scene(scanner::builtin_scene("ibeam-channel"));
    std::vector<scanner::RawScan> raws;
    for (auto& sim : scanner::ScanSimulator(scene).simulate(
             scanner::scan_poses(scene.description().scanner, 2), 1))
        raws.push_back(std::move(sim.raw));
    const PointCloud cloud = scanner::fuse_scans(raws);
    auto grow_with = [&](const KernelTable& k) {
        const detail::KernelOverride use(k);
        return grow_surfaces(cloud, GrowerConfig{});
    };
    const GrowResult base = grow_with(*detail::kernels_for("baseline"));
    ASSERT_GT(base.surfaces.size(), 1000u);
    for (const KernelTable* t : wider) {
        SCOPED_TRACE(t->isa);
        const GrowResult r = grow_with(*t);
        EXPECT_EQ(r.labels, base.labels);
        ASSERT_EQ(r.surfaces.size(), base.surfaces.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < r.surfaces.size(); ++i) {
            const Surface& a = r.surfaces[i];
            const Surface& b = base.surfaces[i];
            differ +=
                std::memcmp(a.normal.data(), b.normal.data(), sizeof(double) * 3) != 0 ||
                std::memcmp(a.centroid.data(), b.centroid.data(), sizeof(double) * 3) != 0 ||
                std::memcmp(a.eigenvalues.data(), b.eigenvalues.data(), sizeof(double) * 3) != 0 ||
                a.point_count != b.point_count ||
                std::memcmp(&a.tolerance, &b.tolerance, sizeof(double)) != 0;
        }
        EXPECT_EQ(differ, 0u);
    }
}
