// The inner loops of surface growing, compiled once per instruction set and chosen at run time on
// the CPU found (docs/performance.md, "Portable binaries"). The loops work on plain arrays and
// return plain numbers, so the per-ISA objects share no inline code with the rest of the library.
#pragma once

#include <cstddef>
#include <cstdint>

namespace surfgrow::detail {

/// Lanes per vector in every kernel, whatever the CPU: the sums are then added in one order on
/// every instruction set, and a result is the same bytes on any x86-64 (or other) CPU.
inline constexpr std::uint32_t kKernelLanes = 8;

/// Most points a filter kernel takes per call (it writes at most this many indices).
inline constexpr std::uint32_t kKernelChunk = 256;

/// A cube index's coordinate arrays, readable kKernelLanes floats past every run's end.
struct PointArrays {
    const float* x;
    const float* y;
    const float* z;
};

/// A half-open range [begin, end) of point positions (CubeIndex::Range).
struct IndexRun {
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
};

/// Sums over the points within sqrt(r2) of `home`, relative to home: n, then x, y, z, then
/// xx, xy, xz, yy, yz, zz.
struct RawMoments {
    double v[10];
};

/// A neighbourhood's inliers in a plane's own frame: q = (u, v, r), the coordinates along two
/// in-plane axes and the normal relative to a point c of the plane. `all` holds, over the inliers,
/// the sums of 1, u, v, r, uu, uv, ur, vv, vr, rr; `signed_by[a]` the same sums (but rr) with
/// each point weighted by the sign of its coordinate along axis a (u or v): the two halves of the
/// neighbourhood across that axis are (all + signed) / 2 and (all - signed) / 2.
struct FrameSums {
    double all[10] = {};
    double signed_by[2][9] = {};
};

/// One kernel table per instruction set.
struct KernelTable {
    const char* isa;  ///< "baseline" (the build's own flags), "avx2", "avx512"
    RawMoments (*moments)(PointArrays p, const IndexRun* runs, std::size_t count,
                          const float home[3], float r2);
    /// Writes the indices in `runs` (at most kKernelChunk points in all) of the points within
    /// sqrt(r2) of `p`, and whose label is not `skip` when `labels` is given, in index order;
    /// returns how many. Several runs per call: a neighbourhood's runs are short.
    std::uint32_t (*within)(PointArrays pts, const IndexRun* runs, std::size_t count,
                            const float p[3], float r2, const std::int32_t* labels,
                            std::int32_t skip, std::uint32_t* out);
    /// Writes the indices in `runs` (at most kKernelChunk points in all) of the points within
    /// sqrt(r2) of `home` and within `tolerance` of the plane {q : normal.(q - home) = offset},
    /// with their distances to it, in index order; returns how many.
    std::uint32_t (*on_plane)(PointArrays pts, const IndexRun* runs, std::size_t count,
                              const float home[3], float r2, const float normal[3], float offset,
                              float tolerance, std::uint32_t* out, float* distance);
    FrameSums (*frame_sums)(PointArrays pts, const IndexRun* runs, std::size_t count,
                            const float home[3], float r2, const float c[3], const float u[3],
                            const float v[3], const float n[3], float tolerance);
};

/// The table for this CPU: the widest instruction set it has that the build compiled a table for.
/// The environment variable SURFGROW_SIMD=<isa> caps the choice (baseline: the build's own flags).
const KernelTable& kernels();

/// The table for `isa` ("baseline", "avx2", "avx512"), or nullptr where this build or CPU lacks it.
const KernelTable* kernels_for(const char* isa);

/// Makes kernels() return `table` until the object is destroyed (tests compare the paths).
class KernelOverride {
  public:
    explicit KernelOverride(const KernelTable& table);
    ~KernelOverride();
    KernelOverride(const KernelOverride&) = delete;
    KernelOverride& operator=(const KernelOverride&) = delete;

  private:
    const KernelTable* previous_;
};

}  // namespace surfgrow::detail
