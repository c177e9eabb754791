#include "surfgrow/io/octomap_export.hpp"

#include <octomap/OcTree.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "surfgrow/core/detail/parallel_errors.hpp"
#include "surfgrow/core/error.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"
#include "surfgrow/io/octree_binary.hpp"
#include "surfgrow/io/radix_sort.hpp"

namespace surfgrow::io {

namespace {

octomap::point3d to_point(const Vec3d& p) {
    return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

// The leaf key of `p`, or an error naming what lies out of OctoMap's range.
octomap::OcTreeKey key_of(const octomap::OcTree& tree, const Vec3d& p, const char* what) {
    octomap::OcTreeKey key;
    if (!p.allFinite() || !tree.coordToKeyChecked(p.x(), p.y(), p.z(), key))
        throw Error(
            ErrorCode::kCloudTooLarge,
            cat({"environment.bt: ", what, " (", num(p.x()), ", ", num(p.y()), ", ", num(p.z()),
                 ") lies beyond OctoMap's range of 32768 cells of ", num(tree.getResolution()),
                 " each way from the frame origin; crop the workspace, shift the cloud "
                 "near the origin, or leave environment.bt out (grow --no-octomap)"}));
    return key;
}

PackedLeafKey pack(const octomap::OcTreeKey& k) {
    return std::uint64_t{k[0]} | (std::uint64_t{k[1]} << 16) | (std::uint64_t{k[2]} << 32);
}

octomap::OcTreeKey unpack(std::uint64_t v) {
    return octomap::OcTreeKey(static_cast<octomap::key_type>(v & 0xffff),
                              static_cast<octomap::key_type>((v >> 16) & 0xffff),
                              static_cast<octomap::key_type>((v >> 32) & 0xffff));
}

// A set of leaf keys within a box of keys: a bitmap when the box has at most 2^29 leaves (64 MiB),
// else a vector sorted on demand. Rays from a scanner cross the same leaves again and again, so
// the bitmap turns millions of hash-set insertions into bit operations. The box is widened to
// LeafBitmaps' alignment (rows of whole words, even on y and z), so that a dense set is written
// from its bits.
class LeafSet {
  public:
    LeafSet(const std::array<std::uint64_t, 3>& lo, const std::array<std::uint64_t, 3>& hi) {
        std::uint64_t volume = 1;
        for (std::size_t a = 0; a < 3; ++a) {
            const std::uint64_t step = a == 0 ? 64 : 2;
            lo_[a] = lo[a] / step * step;
            dims_[a] = (hi[a] + step) / step * step - lo_[a];  // hi < 2^16: within the key range
            volume *= dims_[a];                                // at most 2^48: no overflow
        }
        dense_ = volume <= (std::uint64_t{1} << 29);
        if (dense_) bits_.assign((volume + 63) / 64, 0);
    }
    void insert(std::uint64_t key) {
        if (dense_) {
            const std::uint64_t i = index(key);
            bits_[i >> 6] |= std::uint64_t{1} << (i & 63);
        } else {
            keys_.push_back(key);
            if (keys_.size() >= 2 * sorted_ + (std::size_t{1} << 20)) finish();
        }
    }
    [[nodiscard]] bool dense() const { return dense_; }
    // insert() for threads sharing a dense set: an atomic OR (a union: the same bits whatever
    // the order).
    void insert_shared(std::uint64_t key) {
        const std::uint64_t i = index(key);
        const std::uint64_t bit = std::uint64_t{1} << (i & 63);
        std::atomic_ref<std::uint64_t> word(bits_[i >> 6]);
        // Most leaves near a sensor are crossed by many rays: a plain read spares the locked OR.
        if (!(word.load(std::memory_order_relaxed) & bit))
            word.fetch_or(bit, std::memory_order_relaxed);
    }
    // Whether the box of keys [lo, hi] lies within this set's box.
    [[nodiscard]] bool holds(const std::array<std::uint64_t, 3>& lo,
                             const std::array<std::uint64_t, 3>& hi) const {
        for (std::size_t a = 0; a < 3; ++a)
            if (lo[a] < lo_[a] || hi[a] >= lo_[a] + dims_[a]) return false;
        return true;
    }
    // Every key of this dense set into `to`, a dense set whose box holds this one's: whole rows
    // of words, since both boxes start on a multiple of 64 along x.
    void copy_into(LeafSet& to) const {
        const std::uint64_t words = dims_[0] / 64, shift = (lo_[0] - to.lo_[0]) / 64;
        for (std::uint64_t z = 0; z < dims_[2]; ++z)
            for (std::uint64_t y = 0; y < dims_[1]; ++y) {
                const std::uint64_t from = (y + dims_[1] * z) * words;
                const std::uint64_t at =
                    ((y + lo_[1] - to.lo_[1]) + to.dims_[1] * (z + lo_[2] - to.lo_[2])) *
                        (to.dims_[0] / 64) +
                    shift;
                std::copy_n(bits_.begin() + static_cast<std::ptrdiff_t>(from), words,
                            to.bits_.begin() + static_cast<std::ptrdiff_t>(at));
            }
    }
    // Removes every key of `other` (a dense set over the same box) from this dense set.
    void subtract(const LeafSet& other) {
        for (std::size_t w = 0; w < bits_.size(); ++w) bits_[w] &= ~other.bits_[w];
    }
    [[nodiscard]] std::size_t count() const {
        std::size_t n = 0;
        for (const std::uint64_t w : bits_) n += static_cast<std::size_t>(std::popcount(w));
        return n;
    }
    // A dense set's bits as write_octree_bitmaps reads them, with `occupied` over the same box.
    [[nodiscard]] LeafBitmaps bitmaps(const LeafSet& occupied) const {
        LeafBitmaps b;
        for (std::size_t a = 0; a < 3; ++a) {
            b.lo[a] = static_cast<std::uint32_t>(lo_[a]);
            b.dims[a] = static_cast<std::uint32_t>(dims_[a]);
        }
        b.free = bits_;
        b.occupied = occupied.bits_;
        return b;
    }
    void finish() {
        if (dense_) return;
        std::sort(keys_.begin(), keys_.end());
        keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
        sorted_ = keys_.size();
    }
    // The sorted form (a dense set is written from its bits): f(key) for every key of this set
    // not in `other`, in ascending order; both finish()ed.
    template <class F>
    void for_each_not_in(const LeafSet& other, F&& f) const {
        for (const std::uint64_t k : keys_)
            if (!std::binary_search(other.keys_.begin(), other.keys_.end(), k)) f(k);
    }

  private:
    [[nodiscard]] std::uint64_t index(std::uint64_t key) const {
        const std::uint64_t x = (key & 0xffff) - lo_[0], y = ((key >> 16) & 0xffff) - lo_[1],
                            z = (key >> 32) - lo_[2];
        return x + dims_[0] * (y + dims_[1] * z);
    }
    std::array<std::uint64_t, 3> lo_{}, dims_{};
    bool dense_ = true;
    std::vector<std::uint64_t> bits_;
    std::vector<std::uint64_t> keys_;
    std::size_t sorted_ = 0;
};

}  // namespace

// What an OctomapCarver keeps between calls: every distinct ray so far and, when the box of
// its leaves is small enough for a bitmap, the leaves they carved.
struct OctomapCarver::State {
    explicit State(double resolution) : tree(resolution) {}
    octomap::OcTree tree;
    std::size_t consumed = 0;  // points whose rays are in `rays`
    SensorOrigins origins;     // those rays' origins
    // (origin, end leaf) of every distinct ray, sorted.
    std::vector<std::pair<std::uint32_t, std::uint64_t>> rays;
    std::array<std::uint64_t, 3> lo{0xffff, 0xffff, 0xffff}, hi{0, 0, 0};  // of rays' leaves
    std::unique_ptr<LeafSet> carved;  // dense, or null: cast every ray again at each write
    std::uint64_t cast = 0;           // rays whose leaves are in `carved`
};

OctomapCarver::OctomapCarver() = default;
OctomapCarver::~OctomapCarver() = default;
OctomapCarver::OctomapCarver(OctomapCarver&&) noexcept = default;
OctomapCarver& OctomapCarver::operator=(OctomapCarver&&) noexcept = default;

namespace {

// The rays of points [from, cloud.size()): (origin, end leaf), sorted and distinct.
std::vector<std::pair<std::uint32_t, std::uint64_t>> rays_of(const octomap::OcTree& tree,
                                                             const CloudView& cloud,
                                                             std::span<const std::uint8_t> ray_mask,
                                                             const SensorOrigins& origins,
                                                             std::size_t from, int threads) {
    std::vector<std::pair<std::uint32_t, std::uint64_t>> rays;
    // The ray of point i, or false for a point without one (not finite, masked, no origin).
    auto ray_of = [&](std::size_t i, std::uint32_t& origin, std::uint64_t& end) {
        if (!is_finite(cloud.points[i]) || (!ray_mask.empty() && !ray_mask[i])) return false;
        const Vec3d* o = origins.origin_of(cloud, i);
        if (!o) return false;
        origin = static_cast<std::uint32_t>(o - origins.origins.data());
        end = pack(key_of(tree, cloud.points[i].cast<double>(), "a point"));
        return true;
    };
    if (origins.origins.size() <= 0xffff) {
        // One key per ray, origin above the leaf key, collected in parallel chunks (an error
        // names the first bad point, as a serial loop would) and radix-sorted (a tenth of
        // std::sort's time on a million rays).
        const std::size_t n = cloud.size() - from;
        const int team = resolve_threads(threads);
        const std::size_t chunks = team > 1 && n > 65536 ? 8 * static_cast<std::size_t>(team) : 1;
        std::vector<std::vector<std::uint64_t>> part(chunks);
        detail::ParallelErrors errors;
#pragma omp parallel for num_threads(team) schedule(dynamic, 1) if (chunks > 1)
        for (std::size_t k = 0; k < chunks; ++k)
            errors.run(k, [&] {
                std::uint32_t origin = 0;
                std::uint64_t end = 0;
                // Filled here and moved: neighbouring chunks' vectors share a cache line.
                std::vector<std::uint64_t> mine;
                for (std::size_t i = from + k * n / chunks; i < from + (k + 1) * n / chunks; ++i)
                    if (ray_of(i, origin, end)) mine.push_back((std::uint64_t{origin} << 48) | end);
                part[k] = std::move(mine);
            });
        errors.rethrow();
        std::vector<std::uint64_t> packed;
        std::size_t total = 0;
        for (const auto& p : part) total += p.size();
        packed.reserve(total);
        for (auto& p : part) {
            packed.insert(packed.end(), p.begin(), p.end());
            std::vector<std::uint64_t>().swap(p);
        }
        radix_sort(packed, origins.origins.size() > 1 ? 64 : 48);
        packed.erase(std::unique(packed.begin(), packed.end()), packed.end());
        rays.resize(packed.size());
        for (std::size_t r = 0; r < packed.size(); ++r)
            rays[r] = {static_cast<std::uint32_t>(packed[r] >> 48), packed[r] & 0xffffffffffffull};
    } else {
        std::uint32_t origin = 0;
        std::uint64_t end = 0;
        for (std::size_t i = from; i < cloud.size(); ++i)
            if (ray_of(i, origin, end)) rays.emplace_back(origin, end);
        std::sort(rays.begin(), rays.end());
        rays.erase(std::unique(rays.begin(), rays.end()), rays.end());
    }
    return rays;
}

void grow_box(std::array<std::uint64_t, 3>& lo, std::array<std::uint64_t, 3>& hi,
              std::uint64_t key) {
    for (std::size_t a = 0; a < 3; ++a) {
        const std::uint64_t v = (key >> (16 * a)) & 0xffff;
        lo[a] = std::min(lo[a], v);
        hi[a] = std::max(hi[a], v);
    }
}

// Casts `rays` into `carved` (in parallel into a dense set): how many were cast.
std::uint64_t cast_rays(const octomap::OcTree& tree, const SensorOrigins& origins,
                        std::span<const std::pair<std::uint32_t, std::uint64_t>> rays,
                        LeafSet& carved, int threads) {
    std::vector<octomap::point3d> from(origins.origins.size());
    for (std::size_t k = 0; k < origins.origins.size(); ++k) from[k] = to_point(origins.origins[k]);
    const int team = carved.dense() ? resolve_threads(threads) : 1;
    const auto n = static_cast<std::ptrdiff_t>(rays.size());
    std::uint64_t cast = 0;
#pragma omp parallel num_threads(team) if (team > 1 && n > 4096) reduction(+ : cast)
    {
        octomap::KeyRay ray;
        const bool shared = omp_get_num_threads() > 1;
#pragma omp for schedule(dynamic, 1024)
        for (std::ptrdiff_t r = 0; r < n; ++r) {
            const auto& [o, end] = rays[static_cast<std::size_t>(r)];
            if (!tree.computeRayKeys(from[o], tree.keyToCoord(unpack(end)), ray)) continue;
            ++cast;
            for (const octomap::OcTreeKey& key : ray) {
                if (shared) {
                    carved.insert_shared(pack(key));
                } else {
                    carved.insert(pack(key));
                }
            }
        }
    }
    return cast;
}

}  // namespace

OctomapSummary OctomapCarver::write(std::ostream& out, const OccupancyGrid& grid,
                                    const CloudView& cloud, std::span<const std::uint8_t> ray_mask,
                                    const SensorOrigins& origins, int threads) {
    if (!(grid.mu() > 0) || !std::isfinite(grid.mu()))
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"environment.bt: the resolution must be positive, got ", num(grid.mu())}));
    // Rays are kept for one resolution: another grid starts afresh.
    if (!state_ || state_->tree.getResolution() != grid.mu())
        state_ = std::make_unique<State>(grid.mu());
    State& st = *state_;
    octomap::OcTree& tree = st.tree;
    if (!ray_mask.empty() && ray_mask.size() != cloud.size())
        throw Error(ErrorCode::kInternal, "environment.bt: ray mask size differs from the cloud");
    OctomapSummary summary;
    summary.resolution = grid.mu();
    summary.carving = origins.source;

    std::vector<std::uint64_t> occupied;
    occupied.reserve(grid.size());
    for (const CellCoords& c : grid.cells())
        occupied.push_back(pack(key_of(tree, grid.centre(c), "an occupied cube")));
    std::sort(occupied.begin(), occupied.end());
    if (std::adjacent_find(occupied.begin(), occupied.end()) != occupied.end())
        throw Error(ErrorCode::kInternal, "environment.bt: two cubes share an OctoMap leaf");

    // What was cast before still holds when the cloud only grew and its first origins stayed.
    const bool first = st.consumed == 0 && st.rays.empty();
    const bool grown =
        first ||
        (cloud.size() >= st.consumed && origins.source == st.origins.source &&
         origins.origins.size() >= st.origins.origins.size() &&
         std::equal(st.origins.origins.begin(), st.origins.origins.end(), origins.origins.begin()));
    if (!grown) {
        state_.reset();
        return write(out, grid, cloud, ray_mask, origins, threads);
    }
    // Everything that can fail on the input (a point or origin beyond OctoMap's range) is
    // found before the state changes; a failure after (out of memory) starts it afresh.
    std::vector<std::pair<std::uint32_t, std::uint64_t>> fresh;
    if (origins.known()) fresh = rays_of(tree, cloud, ray_mask, origins, st.consumed, threads);
    // Rays already cast (an origin seen before, an end leaf reached before) are not cast again.
    fresh.erase(std::remove_if(fresh.begin(), fresh.end(),
                               [&](const auto& r) {
                                   return std::binary_search(st.rays.begin(), st.rays.end(), r);
                               }),
                fresh.end());
    std::array<std::uint64_t, 3> rays_lo = st.lo, rays_hi = st.hi;
    for (const auto& [o, end] : fresh) {
        grow_box(rays_lo, rays_hi, end);
        grow_box(rays_lo, rays_hi, pack(key_of(tree, origins.origins[o], "a sensor origin")));
    }
    std::vector<std::uint64_t> free;  // the sorted form's free leaves
    bool written = false;             // the dense form writes as it goes
    try {
        st.consumed = cloud.size();
        st.origins = origins;
        st.lo = rays_lo;
        st.hi = rays_hi;
        const std::size_t before = st.rays.size();
        st.rays.insert(st.rays.end(), fresh.begin(), fresh.end());
        std::inplace_merge(st.rays.begin(), st.rays.begin() + static_cast<std::ptrdiff_t>(before),
                           st.rays.end());

        if (!st.rays.empty()) {
            // Every leaf a ray crosses lies in the box of its two end leaves.
            std::array<std::uint64_t, 3> lo = st.lo, hi = st.hi;
            for (const std::uint64_t key : occupied) grow_box(lo, hi, key);
            if (st.carved && st.carved->holds(lo, hi)) {
                st.cast += cast_rays(tree, origins, fresh, *st.carved, threads);
            } else {
                // A new box (or the first): the leaves carved so far move over, whole rows of bits.
                auto carved = std::make_unique<LeafSet>(lo, hi);
                if (carved->dense() && st.carved) {
                    st.carved->copy_into(*carved);
                    st.cast += cast_rays(tree, origins, fresh, *carved, threads);
                } else {
                    st.cast = cast_rays(tree, origins, st.rays, *carved, threads);
                }
                st.carved = std::move(carved);
            }
            summary.rays = st.cast;
            LeafSet blocked(lo, hi);
            for (const std::uint64_t key : occupied) blocked.insert(key);
            for (const auto& r : st.rays) blocked.insert(r.second);
            if (st.carved->dense()) {
                // Written from the bits: listing and sorting millions of free leaves cost 4x
                // the rays themselves (0.6 s on four fused scans). A carver used once may spend
                // its bits; one that is kept subtracts from a copy.
                const std::unique_ptr<LeafSet> spent =
                    keep_ ? std::make_unique<LeafSet>(*st.carved) : std::move(st.carved);
                LeafSet& carved = *spent;
                carved.subtract(blocked);
                LeafSet occupied_set(lo, hi);
                for (const std::uint64_t key : occupied) occupied_set.insert(key);
                summary.free = carved.count();
                write_octree_bitmaps(out, grid.mu(), carved.bitmaps(occupied_set),
                                     resolve_threads(threads));
                written = true;
            } else {
                // Too wide a box for a bitmap: the sparse set is rebuilt at every write.
                blocked.finish();
                st.carved->finish();
                st.carved->for_each_not_in(blocked,
                                           [&](std::uint64_t key) { free.push_back(key); });
                st.carved.reset();
            }
        }

        if (!written) {
            write_octree_binary(out, grid.mu(), free, occupied);
            summary.free = free.size();
        }
    } catch (...) {
        state_.reset();
        throw;
    }

    if (!out)
        throw Error(ErrorCode::kCannotWrite, "environment.bt: the OctoMap could not be written");
    summary.occupied = occupied.size();
    return summary;
}

OctomapSummary write_octomap_bt(std::ostream& out, const OccupancyGrid& grid,
                                const CloudView& cloud, std::span<const std::uint8_t> ray_mask,
                                const SensorOrigins& origins, int threads) {
    OctomapCarver carver;
    carver.keep_ = false;
    return carver.write(out, grid, cloud, ray_mask, origins, threads);
}

}  // namespace surfgrow::io
