// `surfgrow scan --scene NAME|file.json --poses N|file -o DIR`: simulate a multi-pose scan.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "scan_job.hpp"

namespace surfgrow::cli {

void add_scan_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "scan",
        "Simulate a tilting-laser scan of a scene from several poses (raw scans, fused "
        "cloud with ground truth, truth faces, scene, poses)");
    struct Args {
        ScanSettings scan;
        std::string out = "scan";
        bool quiet = false;
    };
    auto args = std::make_shared<Args>();
    args->scan.add_to(*cmd);
    cmd->add_option("-o,--out", args->out, "Output folder (created; outputs replaced as a whole)")
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        const ScanData data = run_scan(args->scan);
        write_scan_outputs(args->out, data, args->scan);
        if (args->quiet) return;
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "%s: %zu scans -> %zu points (simulated in %.2f s, fused in %.3f s)",
                      data.scene->description().name.c_str(), data.raws.size(), data.cloud.size(),
                      data.simulate_seconds, data.fuse_seconds);
        std::cout << buf << std::endl;
    });
}

}  // namespace surfgrow::cli
