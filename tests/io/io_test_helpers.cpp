#include "io_test_helpers.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>

namespace surfgrow::test {

PointCloud sample_cloud(std::size_t n, uint64_t seed, bool with_nan, bool with_labels) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> uni(-5.0f, 5.0f);
    PointCloud cloud;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t i = 0; i < n; ++i) {
        if (with_nan && i % 7 == 3) {
            cloud.points.emplace_back(nan, nan, nan);
        } else {
            cloud.points.emplace_back(uni(rng), uni(rng), uni(rng));
        }
        if (with_labels) cloud.labels.push_back(static_cast<int32_t>(i % 10) - 1);
    }
    return cloud;
}

PointCloud georeferenced_cloud(std::size_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> uni(-50.0f, 50.0f);
    PointCloud cloud;
    cloud.offset = Vec3d(512345, 5412345, 312);
    for (std::size_t i = 0; i < n; ++i) cloud.points.emplace_back(uni(rng), uni(rng), uni(rng));
    return cloud;
}

void add_normals(PointCloud& cloud, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    cloud.normals.clear();
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        Vec3f n(gauss(rng), gauss(rng), gauss(rng));
        cloud.normals.push_back(n / n.norm());
    }
    const float tricky = std::bit_cast<float>(0x15ae43fdU);  // 7.038531e-26
    const Vec3f special[] = {
        {tricky, -tricky, 1.0f},
        {std::numeric_limits<float>::quiet_NaN(), 0.0f, -0.0f},
        {std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::max(), 0.1f},
        {-1.0f, std::numeric_limits<float>::min(), 1e-7f},
    };
    for (std::size_t k = 0; k < std::size(special) && k < cloud.size(); ++k) {
        cloud.normals[(k * 5 + 1) % cloud.size()] = special[k];
    }
}

void expect_same_normals(const PointCloud& expected, const PointCloud& actual) {
    ASSERT_EQ(expected.normals.size(), actual.normals.size());
    for (std::size_t i = 0; i < expected.normals.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            const float e = expected.normals[i][a];
            const float g = actual.normals[i][a];
            if (std::isnan(e)) {
                ASSERT_TRUE(std::isnan(g)) << "normal " << i << " axis " << a;
            } else {
                ASSERT_EQ(std::bit_cast<uint32_t>(e), std::bit_cast<uint32_t>(g))
                    << "normal " << i << " axis " << a << ": " << e << " came back as " << g;
            }
        }
    }
}

void expect_same_cloud(const PointCloud& expected, const PointCloud& actual, double tolerance) {
    ASSERT_EQ(expected.size(), actual.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            const float e = expected.points[i][a];
            const float g = actual.points[i][a];
            if (std::isnan(e)) {
                ASSERT_TRUE(std::isnan(g)) << "point " << i << " axis " << a;
                continue;
            }
            const double ea = static_cast<double>(e) + expected.offset[a];
            const double ga = static_cast<double>(g) + actual.offset[a];
            ASSERT_NEAR(ea, ga, tolerance) << "point " << i << " axis " << a;
        }
    }
    EXPECT_EQ(expected.labels, actual.labels);
}

std::string written(const std::function<void(std::ostream&)>& writer) {
    std::ostringstream out(std::ios::binary);
    writer(out);
    return out.str();
}

std::string expect_error(const std::function<void()>& f, ErrorCode code, std::string_view needle) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(static_cast<int>(code), static_cast<int>(e.code())) << e.what();
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
            << "message '" << e.what() << "' lacks '" << needle << "'";
        return e.what();
    }
    ADD_FAILURE() << "expected an Error with code " << static_cast<int>(code);
    return {};
}

}  // namespace surfgrow::test
