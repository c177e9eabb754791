// Helpers shared by the test executables: temporary folders, optional real data, synthetic planes.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>  // Vec3d::cross in Rect::normal() and sample_rect

#include <cstdint>
#include <filesystem>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "surfgrow/core/geometry.hpp"
#include "surfgrow/core/point_cloud.hpp"
#include "surfgrow/planes/polygon2d.hpp"

namespace surfgrow::test {

/// True in the ASan+UBSan build (SURFGROW_SANITIZE), where code runs 5-20x slower.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderSanitizers = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif
#else
inline constexpr bool kUnderSanitizers = false;
#endif

/// Skips a full-scale accuracy test (whole scenes, real scans, every thread count) in the
/// sanitizer build: the Release build runs it, and the sanitizers see the same code in the
/// smaller tests; the full-scale ones alone took a third of CI's sanitizer stage.
#define SURFGROW_SKIP_UNDER_SANITIZERS()                                                    \
    do {                                                                                    \
        if (::surfgrow::test::kUnderSanitizers)                                             \
            GTEST_SKIP() << "full-scale accuracy: checked by the Release build, not under " \
                            "the sanitizers";                                               \
    } while (false)

/// The repository root (tests run from there; SURFGROW_SOURCE_DIR is set by CTest).
std::filesystem::path source_dir();

/// ../shared/data/real beside the checkout, if present. Tests that need it call
/// GTEST_SKIP() when this is empty: a user's clone has no ../shared.
std::optional<std::filesystem::path> real_data_dir();

/// A fresh empty folder, removed when the object goes out of scope.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }
    [[nodiscard]] std::filesystem::path operator/(const std::string& name) const {
        return path_ / name;
    }

  private:
    std::filesystem::path path_;
};

/// Reads a whole file as bytes (for byte-identity checks).
std::string read_bytes(const std::filesystem::path& file);
/// Writes bytes to a file, replacing it.
void write_bytes(const std::filesystem::path& file, const std::string& bytes);

/// A planar rectangle: centre, two orthogonal in-plane unit axes, half sizes.
struct Rect {
    Vec3d center;
    Vec3d u;
    Vec3d v;
    double half_u;
    double half_v;
    [[nodiscard]] Vec3d normal() const { return u.cross(v).normalized(); }
};

/// Samples a rectangle on a square grid of `spacing` with uniform jitter of +-jitter*spacing in
/// the plane and Gaussian noise of `sigma` along the normal. Appends points and, if `labels` is
/// given, `label` for each point.
void sample_rect(const Rect& rect, double spacing, double jitter, double sigma,
                 std::mt19937_64& rng, std::vector<Vec3f>& points,
                 std::vector<int32_t>* labels = nullptr, int32_t label = 0);

/// A cluster of three tilted planar patches (24 x 24 points each, about 60 steps across) on the
/// integer lattice of `step` at `base`: rounding to the lattice is their noise, plus one step on
/// one point in ten. Positions are exact floats while base / step + 64 < 2^24, so a cluster moved
/// by a whole number of steps keeps its exact shape at any distance.
void lattice_patches(double step, const Vec3d& base, std::uint64_t seed,
                     std::vector<Vec3f>& points);

/// The mu whose cube side (mu enlarged by one part in 2^20, rounded) is exactly `side`.
double mu_for_cube_side(double side);

/// An axis-aligned box's outer faces as rectangles (6 faces, ids 0..5).
std::vector<Rect> box_faces(const Vec3d& min, const Vec3d& max);

/// Outer faces of a steel I-beam along x: two flanges (top and bottom faces of each) and the web's
/// two sides, the visible faces a scanner sees from beside it. Dimensions in metres.
std::vector<Rect> ibeam_faces(double length, double height, double flange_width,
                              double flange_thickness, double web_thickness);

/// Median of a vector (copied); NaN when empty.
double median(std::vector<double> values);
/// q-quantile (0..1) by nearest rank; NaN when empty.
double quantile(std::vector<double> values, double q);

/// The length of every ring of the polygons, outer rings and holes.
[[nodiscard]] inline double boundary_length(std::span<const PolygonWithHoles> polygons) {
    double sum = 0;
    const auto add = [&](const Ring& ring) {
        for (std::size_t i = 0; i < ring.size(); ++i)
            sum += (ring[(i + 1) % ring.size()] - ring[i]).norm();
    };
    for (const PolygonWithHoles& poly : polygons) {
        add(poly.outer);
        for (const Ring& hole : poly.holes) add(hole);
    }
    return sum;
}

}  // namespace surfgrow::test
