// write_octree_binary: the bytes liboctomap itself writes for the same leaves (set to their
// clamping values, maximum likelihood, pruned), on leaf sets built to exercise pruning: whole
// aligned blocks of one state, blocks with one odd leaf, scattered leaves, the ends of the key
// range and the frame origin, where the root's children meet; and write_octree_bitmaps, the same
// tree from bitmaps over a box of leaves, against the sorted form.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "surfgrow/core/error.hpp"
#include "surfgrow/io/octree_binary.hpp"

namespace surfgrow {
namespace {

using io::PackedLeafKey;

PackedLeafKey key(unsigned x, unsigned y, unsigned z) {
    return std::uint64_t{x} | (std::uint64_t{y} << 16) | (std::uint64_t{z} << 32);
}

octomap::OcTreeKey unpack(PackedLeafKey k) {
    return octomap::OcTreeKey(static_cast<octomap::key_type>(k & 0xffff),
                              static_cast<octomap::key_type>((k >> 16) & 0xffff),
                              static_cast<octomap::key_type>((k >> 32) & 0xffff));
}

struct Leaves {
    std::vector<PackedLeafKey> free, occupied;

    void block(unsigned x0, unsigned y0, unsigned z0, unsigned side, bool occupied_block) {
        for (unsigned z = z0; z < z0 + side; ++z)
            for (unsigned y = y0; y < y0 + side; ++y)
                for (unsigned x = x0; x < x0 + side; ++x)
                    (occupied_block ? occupied : free).push_back(key(x, y, z));
    }
};

// What liboctomap writes: the tree built node by node, as surfgrow did before.
struct Reference {
    std::uint64_t size = 0;
    std::string data;
};

Reference octomap_reference(double resolution, const Leaves& leaves) {
    octomap::OcTree tree(resolution);
    for (const PackedLeafKey k : leaves.free)
        tree.setNodeValue(unpack(k), tree.getClampingThresMinLog(), true);
    for (const PackedLeafKey k : leaves.occupied)
        tree.setNodeValue(unpack(k), tree.getClampingThresMaxLog(), true);
    tree.updateInnerOccupancy();
    tree.toMaxLikelihood();
    tree.prune();
    std::ostringstream data;
    tree.writeBinaryData(data);
    return {tree.size(), data.str()};
}

int bitmap_checks = 0;  // how many leaf sets the bitmap form was compared on

void expect_same_as_octomap(const Leaves& leaves, double resolution = 0.012) {
    std::ostringstream out;
    const std::uint64_t nodes =
        io::write_octree_binary(out, resolution, leaves.free, leaves.occupied);
    const std::string bytes = out.str();
    const Reference ref = octomap_reference(resolution, leaves);
    EXPECT_EQ(nodes, ref.size);
    const std::size_t at = bytes.find("\ndata\n");
    ASSERT_NE(at, std::string::npos);
    EXPECT_NE(bytes.find("\nsize " + std::to_string(ref.size) + "\n"), std::string::npos);
    EXPECT_TRUE(bytes.substr(at + 6) == ref.data)
        << "data differs: " << bytes.size() - at - 6 << " bytes vs " << ref.data.size();
    // The bitmap form writes the same bytes, where the leaves' box is small enough to test.
    std::array<std::uint32_t, 3> lo{65535, 65535, 65535}, hi{0, 0, 0};
    for (const auto* list : {&leaves.free, &leaves.occupied})
        for (const PackedLeafKey k : *list)
            for (std::size_t a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], static_cast<std::uint32_t>((k >> (16 * a)) & 0xffff));
                hi[a] = std::max(hi[a], static_cast<std::uint32_t>((k >> (16 * a)) & 0xffff));
            }
    io::LeafBitmaps b;
    std::uint64_t volume = 1;
    const bool any = !leaves.free.empty() || !leaves.occupied.empty();
    for (std::size_t a = 0; a < 3 && any; ++a) {
        const std::uint32_t step = a == 0 ? 64 : 2;
        b.lo[a] = lo[a] / step * step;
        b.dims[a] = (hi[a] + step) / step * step - b.lo[a];
        volume *= b.dims[a];
    }
    if (any && volume <= (std::uint64_t{1} << 26)) {
        std::vector<std::uint64_t> free_bits((volume + 63) / 64), occupied_bits(free_bits.size());
        auto set = [&](std::vector<std::uint64_t>& bits, PackedLeafKey k) {
            const std::uint64_t x = (k & 0xffff) - b.lo[0], y = ((k >> 16) & 0xffff) - b.lo[1],
                                z = (k >> 32) - b.lo[2];
            const std::uint64_t i = x + b.dims[0] * (y + std::uint64_t{b.dims[1]} * z);
            bits[i >> 6] |= std::uint64_t{1} << (i & 63);
        };
        for (const PackedLeafKey k : leaves.free) set(free_bits, k);
        for (const PackedLeafKey k : leaves.occupied) set(occupied_bits, k);
        b.free = free_bits;
        b.occupied = occupied_bits;
        std::ostringstream from_bits;
        EXPECT_EQ(io::write_octree_bitmaps(from_bits, resolution, b), nodes);
        EXPECT_TRUE(from_bits.str() == bytes) << "the bitmap form differs";
        std::ostringstream on_two;  // the bottom level split between threads
        (void)io::write_octree_bitmaps(on_two, resolution, b, 2);
        EXPECT_TRUE(on_two.str() == bytes) << "the bitmap form differs on two threads";
        ++bitmap_checks;
    }
    // And liboctomap reads it back.
    std::istringstream in(bytes);
    octomap::OcTree back(0.1);
    ASSERT_TRUE(back.readBinary(in));
    EXPECT_EQ(back.size(), ref.size);
    EXPECT_DOUBLE_EQ(back.getResolution(), resolution);
}

TEST(OctreeBinary, AlignedBlocksOfOneStateBecomeOneLeaf) {
    Leaves l;
    l.block(32768, 32768, 32768, 8, false);       // one free leaf 3 levels up
    l.block(32768 + 16, 32768, 32768, 16, true);  // one occupied leaf 4 levels up
    l.block(32768, 32768 + 32, 32768, 2, false);
    expect_same_as_octomap(l);
}

TEST(OctreeBinary, BlocksWithOneOddLeafOrUnalignedStayExpanded) {
    Leaves l;
    l.block(100, 200, 300, 8, false);  // aligned, but one leaf is occupied instead
    l.free.erase(std::find(l.free.begin(), l.free.end(), key(103, 205, 301)));
    l.occupied.push_back(key(103, 205, 301));
    l.block(1001, 1001, 1001, 8, true);   // not aligned: no whole node
    l.block(2000, 2000, 2000, 4, false);  // aligned 4^3 but one leaf missing (unknown)
    l.free.pop_back();
    expect_same_as_octomap(l);
}

TEST(OctreeBinary, ScatteredLeavesAcrossTheRootsChildren) {
    std::mt19937 rng(5);
    std::uniform_int_distribution<unsigned> near(32768 - 40, 32768 + 40);
    Leaves l;
    std::vector<PackedLeafKey> all;
    for (int i = 0; i < 20000; ++i) all.push_back(key(near(rng), near(rng), near(rng)));
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    std::shuffle(all.begin(), all.end(), rng);  // any order in
    for (std::size_t i = 0; i < all.size(); ++i) (i % 3 ? l.free : l.occupied).push_back(all[i]);
    // Whole blocks among them, and the far ends of the key range.
    l.block(32768 - 80, 32768 - 80, 32768 - 80, 16, false);
    l.occupied.push_back(key(0, 0, 0));
    l.free.push_back(key(65535, 65535, 65535));
    l.free.push_back(key(65535, 0, 65535));
    expect_same_as_octomap(l);
}

TEST(OctreeBinary, OneLeafAndNoLeaf) {
    Leaves one;
    one.occupied.push_back(key(32768, 32767, 12));
    expect_same_as_octomap(one);
    Leaves none;
    std::ostringstream out;
    EXPECT_EQ(io::write_octree_binary(out, 0.05, {}, {}), 0u);
    EXPECT_TRUE(out.str().ends_with("size 0\nres 0.050000000000000003\ndata\n")) << out.str();
    expect_same_as_octomap(none, 0.05);
}

TEST(OctreeBinary, ALeafListedTwiceIsAnInternalError) {
    Leaves l;
    l.free.push_back(key(1, 2, 3));
    l.occupied.push_back(key(1, 2, 3));
    std::ostringstream out;
    EXPECT_THROW((void)io::write_octree_binary(out, 0.012, l.free, l.occupied), Error);
}

TEST(OctreeBinary, TheBitmapFormMatchesOnRandomBoxesOfMixedStates) {
    // Dense random leaves in boxes at odd offsets, with whole free and occupied blocks inside:
    // every level of the bitmap form's pyramid meets mixed, pruned and unknown cells.
    std::mt19937 rng(11);
    const int before = bitmap_checks;
    for (int trial = 0; trial < 6; ++trial) {
        std::uniform_int_distribution<unsigned> base(1000, 60000), side(3, 70);
        const unsigned x0 = base(rng), y0 = base(rng), z0 = base(rng);
        const unsigned sx = side(rng), sy = side(rng), sz = side(rng);
        std::uniform_real_distribution<double> u(0, 1);
        const double fill = 0.1 + 0.8 * u(rng);
        Leaves l;
        l.block(x0 / 16 * 16 + 16, y0 / 16 * 16, z0 / 16 * 16, 16, trial % 2 == 0);
        for (unsigned z = z0; z < z0 + sz; ++z)
            for (unsigned y = y0; y < y0 + sy; ++y)
                for (unsigned x = x0; x < x0 + sx; ++x) {
                    const PackedLeafKey k = key(x, y, z);
                    if (std::find(l.free.begin(), l.free.end(), k) != l.free.end() ||
                        std::find(l.occupied.begin(), l.occupied.end(), k) != l.occupied.end())
                        continue;
                    const double r = u(rng);
                    if (r < fill)
                        l.free.push_back(k);
                    else if (r < fill + 0.05)
                        l.occupied.push_back(k);
                }
        expect_same_as_octomap(l);
    }
    EXPECT_EQ(bitmap_checks - before, 6);
}

TEST(OctreeBinary, TheBitmapFormRefusesAnUnalignedBox) {
    std::vector<std::uint64_t> bits(4, 0);
    io::LeafBitmaps b;
    b.lo = {32, 0, 0};  // not a multiple of 64
    b.dims = {64, 2, 2};
    b.free = bits;
    b.occupied = bits;
    std::ostringstream out;
    EXPECT_THROW((void)io::write_octree_bitmaps(out, 0.012, b), Error);
    b.lo = {64, 0, 0};
    b.dims = {64, 2, 4};  // 8 words needed
    EXPECT_THROW((void)io::write_octree_bitmaps(out, 0.012, b), Error);
}

}  // namespace
}  // namespace surfgrow
