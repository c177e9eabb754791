// OctoMap's binary OcTree stream (.bt), written straight from leaf keys.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>
#include <span>

namespace surfgrow::io {

/// A leaf key in one integer: OctoMap's 16-bit key of each axis, x in bits 0-15, y 16-31, z 32-47.
using PackedLeafKey = std::uint64_t;

/// Writes the OcTree whose full-depth (16) leaves are `free_leaves` and `occupied_leaves`
/// (disjoint; any order; duplicates not allowed) at `resolution`, in OctoMap's .bt format:
/// header ("# Octomap OcTree binary file", id OcTree, size, res) and OcTree::writeBinaryData.
///
/// The bytes are those liboctomap writes after setting each leaf to its clamping value,
/// toMaxLikelihood() and prune() (tests/io compare them), computed from the keys sorted in Morton
/// order instead of building the tree: a node whose whole cube is leaves of one state is one
/// leaf, as prune() makes it. OctoMap's node-by-node build took 1.5 s for 3 million free leaves.
/// Returns the number of nodes (the header's size).
std::uint64_t write_octree_binary(std::ostream& out, double resolution,
                                  std::span<const PackedLeafKey> free_leaves,
                                  std::span<const PackedLeafKey> occupied_leaves);

/// Leaves given as two bitmaps over a box of keys: leaf lo + (x, y, z) is bit
/// x + dims[0] * (y + dims[1] * z) of `free` or of `occupied` (disjoint; bit i in word i / 64 at
/// i % 64). The box is aligned for the writer: lo[0] and dims[0] multiples of 64 (each row of
/// leaves starts a word), lo and dims even on y and z; and it lies within the key range.
struct LeafBitmaps {
    std::array<std::uint32_t, 3> lo{};
    std::array<std::uint32_t, 3> dims{};
    std::span<const std::uint64_t> free, occupied;
};

/// The same bytes as write_octree_binary for the leaves of `leaves`, without listing them: each
/// level's cell states (unknown, free, occupied, mixed) are derived from the one below, 32 cells
/// per word at the leaves, and the tree is written top-down from them. Linear in the box's
/// volume rather than in the number of leaves: the form for rays carved through a dense box.
/// The bottom level is derived on `threads` threads (the same bytes for any number). Throws
/// Error(kInternal) if the box is not aligned or the bitmaps are too short.
std::uint64_t write_octree_bitmaps(std::ostream& out, double resolution, const LeafBitmaps& leaves,
                                   int threads = 1);

}  // namespace surfgrow::io
