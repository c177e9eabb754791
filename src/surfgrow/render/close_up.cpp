#include "surfgrow/render/close_up.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

#include "surfgrow/render/disk_grid.hpp"
#include "surfgrow/render/framing.hpp"

namespace surfgrow::render {

namespace {

constexpr std::size_t kCandidates = 40;  // the largest groups tried
constexpr std::size_t kMinDisks = 10;    // a group smaller than this is no face
constexpr std::size_t kMinInView = 3;    // disks of each face within the close-up
constexpr std::size_t kEdgeSamples = 256;
const double kMaxCos = std::cos(40.0 * 3.14159265358979323846 / 180.0);

struct Face {
    std::int32_t id = -1;
    std::size_t count = 0;
    Vec3d normal = Vec3d::Zero();  // sum, then unit
    Vec3d centroid = Vec3d::Zero();
    std::vector<std::uint32_t> disks;
};

}  // namespace

std::optional<CloseUp> find_corner(std::span<const Disk> disks,
                                   std::span<const std::int32_t> groups) {
    if (groups.size() != disks.size()) return std::nullopt;
    const double half = kCloseUpRadii * median_disk_radius(disks);
    if (!(half > 0)) return std::nullopt;

    // The largest groups, with their mean normal and centroid.
    std::vector<std::int32_t> ids;
    for (std::size_t i = 0; i < disks.size(); ++i)
        if (groups[i] >= 0 && usable(disks[i])) ids.push_back(groups[i]);
    std::sort(ids.begin(), ids.end());
    std::vector<Face> faces;
    for (std::size_t k = 0; k < ids.size();) {
        std::size_t e = k;
        while (e < ids.size() && ids[e] == ids[k]) ++e;
        faces.push_back({ids[k], e - k, Vec3d::Zero(), Vec3d::Zero(), {}});
        k = e;
    }
    std::stable_sort(faces.begin(), faces.end(),
                     [](const Face& a, const Face& b) { return a.count > b.count; });
    while (!faces.empty() && (faces.size() > kCandidates || faces.back().count < kMinDisks))
        faces.pop_back();
    std::vector<Vec3d> centers(disks.size(), Vec3d::Constant(NAN));
    std::vector<std::int32_t> face_of(disks.size(), -1);
    for (std::size_t i = 0; i < disks.size(); ++i) {
        if (groups[i] < 0 || !usable(disks[i])) continue;
        for (std::size_t f = 0; f < faces.size(); ++f)
            if (faces[f].id == groups[i]) {
                face_of[i] = static_cast<std::int32_t>(f);
                faces[f].normal += disks[i].normal.normalized();
                faces[f].centroid += disks[i].center;
                faces[f].disks.push_back(static_cast<std::uint32_t>(i));
                centers[i] = disks[i].center;
                break;
            }
    }
    for (Face& f : faces) {
        f.centroid /= double(f.count);
        f.normal = f.normal.norm() > 0.5 * double(f.count) ? Vec3d(f.normal.normalized())
                                                           : Vec3d::Zero();  // not one plane
    }
    const DiskGrid grid(centers, half);
    // Disks of face f within the close-up around p.
    auto in_view = [&](const Vec3d& p, std::span<const std::size_t> of) {
        std::array<std::size_t, 3> n{};
        for (const std::uint32_t c : grid.around(p))
            for (const std::uint32_t i : grid.points_in(c)) {
                if ((disks[i].center - p).squaredNorm() > half * half) continue;
                for (std::size_t k = 0; k < of.size(); ++k)
                    if (face_of[i] == static_cast<std::int32_t>(of[k])) ++n[k];
            }
        std::size_t least = n[0];
        for (std::size_t k = 1; k < of.size(); ++k) least = std::min(least, n[k]);
        return least;
    };
    auto apart = [&](std::size_t a, std::size_t b) {
        return faces[a].normal != Vec3d::Zero() && faces[b].normal != Vec3d::Zero() &&
               std::abs(faces[a].normal.dot(faces[b].normal)) < kMaxCos;
    };
    auto looking = [&](const Vec3d& p, Vec3d sum) {
        CloseUp c;
        c.center = p;
        c.half_size = half;
        if (sum.norm() > 0.3) c.forward = -sum.normalized();
        return c;
    };

    std::optional<CloseUp> best;
    std::size_t best_score = kMinInView - 1;
    for (std::size_t a = 0; a < faces.size(); ++a)
        for (std::size_t b = a + 1; b < faces.size(); ++b) {
            if (!apart(a, b)) continue;
            for (std::size_t c = b + 1; c < faces.size(); ++c) {
                if (!apart(a, c) || !apart(b, c)) continue;
                Eigen::Matrix3d m;
                m.row(0) = faces[a].normal, m.row(1) = faces[b].normal, m.row(2) = faces[c].normal;
                if (std::abs(m.determinant()) < 0.3) continue;
                const Vec3d d(faces[a].normal.dot(faces[a].centroid),
                              faces[b].normal.dot(faces[b].centroid),
                              faces[c].normal.dot(faces[c].centroid));
                const Vec3d p = m.partialPivLu().solve(d);
                const std::array<std::size_t, 3> of{a, b, c};
                const std::size_t score = in_view(p, of);
                if (score > best_score) {
                    best_score = score;
                    best = looking(p, faces[a].normal + faces[b].normal + faces[c].normal);
                }
            }
        }
    if (best) return best;

    // An edge: points of the two planes' line near disks of the first face.
    for (std::size_t a = 0; a < faces.size(); ++a)
        for (std::size_t b = a + 1; b < faces.size(); ++b) {
            if (!apart(a, b)) continue;
            const Vec3d na = faces[a].normal, nb = faces[b].normal;
            const Vec3d dir = na.cross(nb).normalized();
            const double da = na.dot(faces[a].centroid), db = nb.dot(faces[b].centroid);
            // A point of the line: the combination of the normals that lies on both planes.
            const double k = na.dot(nb);
            const Vec3d origin =
                ((da - db * k) * na + (db - da * k) * nb) / std::max(1 - k * k, 1e-12);
            const std::size_t step = std::max<std::size_t>(1, faces[a].disks.size() / kEdgeSamples);
            for (std::size_t s = 0; s < faces[a].disks.size(); s += step) {
                const Vec3d& q = disks[faces[a].disks[s]].center;
                const Vec3d p = origin + dir * dir.dot(q - origin);
                const std::array<std::size_t, 2> of{a, b};
                const std::size_t score = in_view(p, of);
                if (score > best_score) {
                    best_score = score;
                    best = looking(p, na + nb);
                }
            }
        }
    return best;
}

}  // namespace surfgrow::render
