#include "surfgrow/io/octree_binary.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <utility>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/radix_sort.hpp"

namespace surfgrow::io {

namespace {

constexpr int kDepth = 16;  // OctoMap's tree depth: 16-bit keys

// Morton (Z-order) code of a packed key, x in the lowest bit of each triple: the order of
// OctoMap's child index (x 1, y 2, z 4), so sorted codes list the leaves depth first.
std::uint64_t spread(std::uint64_t v) {
    v &= 0xffff;
    v = (v | (v << 16)) & 0x0000ff0000ffull;
    v = (v | (v << 8)) & 0x00f00f00f00full;
    v = (v | (v << 4)) & 0x0c30c30c30c3ull;
    v = (v | (v << 2)) & 0x249249249249ull;
    return v;
}

std::uint64_t morton(PackedLeafKey k) {
    return spread(k) | (spread(k >> 16) << 1) | (spread(k >> 32) << 2);
}

// Child states as OcTree::writeBinaryNode codes them, two bits per child.
constexpr unsigned kUnknown = 0, kFree = 1, kOccupied = 2, kInner = 3;

class Writer {
  public:
    explicit Writer(std::vector<std::uint64_t> codes) : codes_(std::move(codes)) {
        occupied_before_.resize(codes_.size() + 1);
        for (std::size_t i = 0; i < codes_.size(); ++i)
            occupied_before_[i + 1] = occupied_before_[i] + (codes_[i] & 1);
    }

    // writeBinaryNode for the node at `depth` whose leaves are codes_[b, e).
    void node(std::size_t b, std::size_t e, int depth) {
        const int shift = 1 + 3 * (kDepth - 1 - depth);  // 1: the state bit below the code
        const std::uint64_t volume = std::uint64_t{1} << (3 * (kDepth - 1 - depth));
        std::array<std::size_t, 9> at{};
        at[0] = b;
        for (unsigned c = 0; c < 8; ++c)
            at[c + 1] = static_cast<std::size_t>(
                std::partition_point(codes_.begin() + static_cast<std::ptrdiff_t>(at[c]),
                                     codes_.begin() + static_cast<std::ptrdiff_t>(e),
                                     [&](std::uint64_t x) { return ((x >> shift) & 7) <= c; }) -
                codes_.begin());
        std::array<unsigned, 8> state{};
        unsigned low = 0, high = 0;
        for (unsigned c = 0; c < 8; ++c) {
            state[c] = state_of(at[c], at[c + 1], volume);
            (c < 4 ? low : high) |= state[c] << (2 * (c % 4));
            nodes_ += state[c] != kUnknown;
        }
        bytes_.push_back(static_cast<char>(low));
        bytes_.push_back(static_cast<char>(high));
        for (unsigned c = 0; c < 8; ++c)
            if (state[c] == kInner) node(at[c], at[c + 1], depth + 1);
    }

    [[nodiscard]] const std::string& bytes() const { return bytes_; }
    [[nodiscard]] std::uint64_t nodes() const { return nodes_; }

  private:
    // A cube wholly of one state is one leaf (prune() after toMaxLikelihood()).
    [[nodiscard]] unsigned state_of(std::size_t b, std::size_t e, std::uint64_t volume) const {
        if (b == e) return kUnknown;
        if (e - b == volume) {
            const std::size_t occupied = occupied_before_[e] - occupied_before_[b];
            if (occupied == 0) return kFree;
            if (occupied == e - b) return kOccupied;
        }
        return kInner;
    }

    std::vector<std::uint64_t> codes_;  // (morton << 1) | occupied, sorted
    std::vector<std::size_t> occupied_before_;
    std::string bytes_;
    std::uint64_t nodes_ = 1;  // the root
};

// OcTree::writeBinary's header, with the resolution at full precision (the library prints 6
// digits, so a resolution like 1/300 would read back off), then the nodes' bytes.
void write_stream(std::ostream& out, double resolution, std::uint64_t nodes,
                  const std::string& data) {
    const auto precision = out.precision(17);
    out << "# Octomap OcTree binary file\n"
        << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
        << "# written by surfgrow: occupied = registered points' cubes, free = carved by rays\n"
        << "id OcTree\nsize " << nodes << "\nres " << resolution << "\ndata\n";
    out.precision(precision);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

// The state of every cell at levels 1 (2 leaves a side) to kDepth (the root) of the leaves of a
// LeafBitmaps, one byte each over the cells the box reaches: as Writer::state_of decides them
// (a cell wholly free or wholly occupied is one leaf, one without leaves unknown).
class LevelStates {
  public:
    LevelStates(const LeafBitmaps& leaves, int threads) : leaves_(leaves) {
        const auto& lo = leaves.lo;
        const auto& dims = leaves.dims;
        if (lo[0] % 64 || dims[0] % 64 || lo[1] % 2 || lo[2] % 2 || dims[1] % 2 || dims[2] % 2)
            throw Error(ErrorCode::kInternal, "environment.bt: the leaf box is not aligned");
        for (int a = 0; a < 3; ++a)
            if (dims[a] == 0 || std::uint64_t{lo[a]} + dims[a] > (std::uint64_t{1} << kDepth))
                throw Error(ErrorCode::kInternal, "environment.bt: the leaf box is out of range");
        const std::uint64_t words = std::uint64_t{dims[0]} / 64 * dims[1] * dims[2];
        if (leaves.free.size() < words || leaves.occupied.size() < words)
            throw Error(ErrorCode::kInternal, "environment.bt: the leaf bitmaps are too short");
        row_words_ = dims[0] / 64;
        leaves_from_bitmaps(threads);
        for (int level = 2; level <= kDepth; ++level) from_level_below(level);
    }

    [[nodiscard]] unsigned root() const { return state(kDepth, 0, 0, 0); }

    // writeBinaryNode for the node at `level` (its children one level down), then its mixed
    // children in child order (x in bit 0, y in bit 1, z in bit 2), depth first.
    void write_node(int level, std::uint32_t x, std::uint32_t y, std::uint32_t z, std::string& data,
                    std::uint64_t& nodes) const {
        std::array<unsigned, 8> child{};
        unsigned low = 0, high = 0;
        for (unsigned c = 0; c < 8; ++c) {
            child[c] = state(level - 1, 2 * x + (c & 1), 2 * y + ((c >> 1) & 1), 2 * z + (c >> 2));
            (c < 4 ? low : high) |= child[c] << (2 * (c % 4));
            nodes += child[c] != kUnknown;
        }
        data.push_back(static_cast<char>(low));
        data.push_back(static_cast<char>(high));
        for (unsigned c = 0; c < 8; ++c)
            if (child[c] == kInner)
                write_node(level - 1, 2 * x + (c & 1), 2 * y + ((c >> 1) & 1), 2 * z + (c >> 2),
                           data, nodes);
    }

  private:
    struct Level {
        std::array<std::uint32_t, 3> lo{}, dims{};  // in cells of this level
        std::vector<std::uint8_t> state;
    };

    // The state of the cell at absolute coordinates (x, y, z) of `level` (0: a leaf).
    [[nodiscard]] unsigned state(int level, std::uint32_t x, std::uint32_t y,
                                 std::uint32_t z) const {
        if (level == 0) {
            const auto& lo = leaves_.lo;
            const auto& dims = leaves_.dims;
            if (x < lo[0] || y < lo[1] || z < lo[2] || x - lo[0] >= dims[0] ||
                y - lo[1] >= dims[1] || z - lo[2] >= dims[2])
                return kUnknown;
            const std::uint64_t i =
                (x - lo[0]) +
                std::uint64_t{dims[0]} * ((y - lo[1]) + std::uint64_t{dims[1]} * (z - lo[2]));
            if ((leaves_.free[i >> 6] >> (i & 63)) & 1) return kFree;
            if ((leaves_.occupied[i >> 6] >> (i & 63)) & 1) return kOccupied;
            return kUnknown;
        }
        const Level& l = levels_[static_cast<std::size_t>(level)];
        if (x < l.lo[0] || y < l.lo[1] || z < l.lo[2] || x - l.lo[0] >= l.dims[0] ||
            y - l.lo[1] >= l.dims[1] || z - l.lo[2] >= l.dims[2])
            return kUnknown;
        return l
            .state[(x - l.lo[0]) + std::size_t{l.dims[0]} *
                                       ((y - l.lo[1]) + std::size_t{l.dims[1]} * (z - l.lo[2]))];
    }

    // Level 1 from the bitmaps: the 2 x 2 leaves of a cell in y and z are four rows, and its 2
    // leaves in x a pair of bits in each, so one word of each row gives 32 cells.
    void leaves_from_bitmaps(int threads) {
        const auto& dims = leaves_.dims;
        Level& l = levels_[1];
        for (int a = 0; a < 3; ++a) {
            l.lo[static_cast<std::size_t>(a)] = leaves_.lo[static_cast<std::size_t>(a)] / 2;
            l.dims[static_cast<std::size_t>(a)] = dims[static_cast<std::size_t>(a)] / 2;
        }
        l.state.assign(std::size_t{l.dims[0]} * l.dims[1] * l.dims[2], kUnknown);
        constexpr std::uint64_t kEven = 0x5555555555555555ull;
        // Each layer of cells writes its own bytes: any thread count gives the same states.
#pragma omp parallel for num_threads(std::max(threads, 1)) schedule(static)
        for (std::uint32_t cz = 0; cz < l.dims[2]; ++cz)
            for (std::uint32_t cy = 0; cy < l.dims[1]; ++cy) {
                std::size_t rows[4];
                for (unsigned r = 0; r < 4; ++r)
                    rows[r] = (std::size_t{2 * cy + (r & 1)} +
                               std::size_t{dims[1]} * (2 * cz + (r >> 1))) *
                              row_words_;
                std::uint8_t* out =
                    &l.state[std::size_t{l.dims[0]} * (cy + std::size_t{l.dims[1]} * cz)];
                for (std::size_t w = 0; w < row_words_; ++w) {
                    std::uint64_t any = 0, all_free = ~std::uint64_t{0},
                                  all_occupied = ~std::uint64_t{0};
                    for (const std::size_t row : rows) {
                        const std::uint64_t f = leaves_.free[row + w],
                                            o = leaves_.occupied[row + w];
                        any |= f | o;
                        all_free &= f;
                        all_occupied &= o;
                    }
                    if (!any) continue;  // 32 unknown cells
                    // Bit 2k of each: the cell of leaves 2k and 2k + 1.
                    any = (any | (any >> 1)) & kEven;
                    all_free &= (all_free >> 1) & kEven;
                    all_occupied &= (all_occupied >> 1) & kEven;
                    for (std::uint64_t m = any; m; m &= m - 1) {
                        const int bit = std::countr_zero(m);
                        const std::uint64_t b = std::uint64_t{1} << bit;
                        out[32 * w + static_cast<std::size_t>(bit / 2)] =
                            static_cast<std::uint8_t>((all_free & b)       ? kFree
                                                      : (all_occupied & b) ? kOccupied
                                                                           : kInner);
                    }
                }
            }
    }

    // Level `level` from the one below: one state if all eight children share it, else mixed.
    void from_level_below(int level) {
        const Level& below = levels_[static_cast<std::size_t>(level - 1)];
        Level& l = levels_[static_cast<std::size_t>(level)];
        for (std::size_t a = 0; a < 3; ++a) {
            l.lo[a] = below.lo[a] / 2;
            l.dims[a] = (below.lo[a] + below.dims[a] - 1) / 2 - l.lo[a] + 1;
        }
        l.state.assign(std::size_t{l.dims[0]} * l.dims[1] * l.dims[2], kUnknown);
        for (std::uint32_t z = 0; z < l.dims[2]; ++z)
            for (std::uint32_t y = 0; y < l.dims[1]; ++y)
                for (std::uint32_t x = 0; x < l.dims[0]; ++x) {
                    const std::uint32_t ax = l.lo[0] + x, ay = l.lo[1] + y, az = l.lo[2] + z;
                    unsigned any = 0, all = 3;
                    for (unsigned c = 0; c < 8; ++c) {
                        const unsigned s = state(level - 1, 2 * ax + (c & 1),
                                                 2 * ay + ((c >> 1) & 1), 2 * az + (c >> 2));
                        any |= s;
                        all &= s;
                    }
                    // all == any: every child the same (unknown, free, occupied or mixed).
                    l.state[x + std::size_t{l.dims[0]} * (y + std::size_t{l.dims[1]} * z)] =
                        static_cast<std::uint8_t>(all == any ? any : kInner);
                }
    }

    const LeafBitmaps& leaves_;
    std::size_t row_words_ = 0;
    std::array<Level, kDepth + 1> levels_;  // [0]: the bitmaps themselves
};

}  // namespace

std::uint64_t write_octree_binary(std::ostream& out, double resolution,
                                  std::span<const PackedLeafKey> free_leaves,
                                  std::span<const PackedLeafKey> occupied_leaves) {
    std::vector<std::uint64_t> codes;
    codes.reserve(free_leaves.size() + occupied_leaves.size());
    for (const PackedLeafKey k : free_leaves) codes.push_back(morton(k) << 1);
    for (const PackedLeafKey k : occupied_leaves) codes.push_back((morton(k) << 1) | 1);
    radix_sort(codes, 1 + 3 * kDepth);
    for (std::size_t i = 1; i < codes.size(); ++i)
        if ((codes[i] >> 1) == (codes[i - 1] >> 1))
            throw Error(ErrorCode::kInternal, "environment.bt: a leaf is listed twice");

    // No leaf: OctoMap has no root, so no node and no data.
    const std::size_t leaves = codes.size();
    Writer w(std::move(codes));
    if (leaves > 0) w.node(0, leaves, 0);
    const std::uint64_t nodes = leaves > 0 ? w.nodes() : 0;
    write_stream(out, resolution, nodes, w.bytes());
    return nodes;
}

std::uint64_t write_octree_bitmaps(std::ostream& out, double resolution, const LeafBitmaps& leaves,
                                   int threads) {
    const LevelStates levels(leaves, threads);
    std::string data;
    std::uint64_t nodes = 0;
    if (levels.root() != kUnknown) {
        nodes = 1;
        levels.write_node(kDepth, 0, 0, 0, data, nodes);
    }
    write_stream(out, resolution, nodes, data);
    return nodes;
}

}  // namespace surfgrow::io
