// The benchmark clouds: simulated scans of the built-in I-beam channel (the paper's setting).
#pragma once

#include <vector>

#include "surfgrow/scanner/builtin_scenes.hpp"
#include "surfgrow/scanner/fuse.hpp"
#include "surfgrow/scanner/scan_simulator.hpp"
#include "surfgrow/scanner/scene.hpp"

namespace surfgrow::bench {

/// `poses` full URG-04LX scans (360 tilts x 768 steps, 5 readings, datasheet noise) of the
/// ibeam-channel scene from poses 0.5 m apart along the channel, fused into one cloud.
inline PointCloud ibeam_channel_scan(int poses, std::uint64_t seed = 1) {
    const scanner::SceneDescription desc = scanner::builtin_scene("ibeam-channel");
    const scanner::Scene scene(desc);
    const scanner::ScanSimulator sim(scene);
    const std::vector<scanner::Pose> path = scanner::scan_poses(desc.scanner, poses);
    std::vector<scanner::RawScan> raws;
    for (auto& s : sim.simulate(path, seed)) raws.push_back(std::move(s.raw));
    return scanner::fuse_scans(raws);
}

}  // namespace surfgrow::bench
