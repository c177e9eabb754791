// write_octree_binary: the bytes liboctomap itself writes for the same leaves (set to their
// clamping values, maximum likelihood, pruned), on leaf sets built to exercise pruning: whole
// aligned blocks of one state, blocks with one odd leaf, scattered leaves, the ends of the key
// range and the frame origin, where the root's children meet.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <algorithm>
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

}  // namespace
}  // namespace surfgrow
