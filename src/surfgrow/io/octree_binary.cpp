#include "surfgrow/io/octree_binary.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "surfgrow/core/error.hpp"

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

// LSD radix sort on the low `bits` bits, 16 at a time: linear in the millions of free leaves.
void radix_sort(std::vector<std::uint64_t>& v, int bits) {
    std::vector<std::uint64_t> tmp(v.size());
    std::vector<std::size_t> count(std::size_t{1} << 16);
    for (int shift = 0; shift < bits; shift += 16) {
        std::fill(count.begin(), count.end(), 0);
        for (const std::uint64_t x : v) ++count[(x >> shift) & 0xffff];
        std::size_t sum = 0;
        for (std::size_t& c : count) sum += std::exchange(c, sum);
        for (const std::uint64_t x : v) tmp[count[(x >> shift) & 0xffff]++] = x;
        v.swap(tmp);
    }
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
    const std::string& data = w.bytes();
    // OcTree::writeBinary's header, with the resolution at full precision (the library prints
    // 6 digits, so a resolution like 1/300 would read back off).
    const auto precision = out.precision(17);
    out << "# Octomap OcTree binary file\n"
        << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
        << "# written by surfgrow: occupied = registered points' cubes, free = carved by rays\n"
        << "id OcTree\nsize " << nodes << "\nres " << resolution << "\ndata\n";
    out.precision(precision);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    return nodes;
}

}  // namespace surfgrow::io
