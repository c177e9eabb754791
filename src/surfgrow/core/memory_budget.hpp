// How much memory one input or one picture may plan to take: a clear error beats an OOM kill.
#pragma once

#include <cstdint>
#include <string_view>

namespace surfgrow {

/// The bytes one file read or one picture may plan to use: the machine's physical memory, or
/// SURFGROW_MEMORY_LIMIT where it is set (a number of bytes with an optional K, M, G or T suffix,
/// powers of 1024: a shared machine, a container, a test). Throws Error(kUsage) for a malformed
/// SURFGROW_MEMORY_LIMIT.
[[nodiscard]] std::uint64_t memory_budget();

/// Throws Error(kCloudTooLarge, "<what> needs about X MB of memory, more than the Y MB ...")
/// when `bytes` exceed memory_budget(). `what` names the input and the work ("file.json: parsing
/// its 2.1 GB of JSON").
void check_memory(double bytes, std::string_view what);

}  // namespace surfgrow
