// `surfgrow acquire -o scan.sgraw|DIR [--port ...] [--emulate SCENE]`: one tilting scan from a
// URG-04LX over SCIP 2.0 and a DYNAMIXEL tilt servo, written as a raw scan (docs/scanner.md,
// "Acquiring a scan"). With --emulate both devices are emulated behind pseudo-terminals and the
// scan is taken through the same serial path.
#include <cstdio>
#include <iostream>

#include "acquire_job.hpp"
#include "commands.hpp"

namespace surfgrow::cli {

void add_acquire_command(CLI::App& app) {
    auto* cmd = app.add_subcommand(
        "acquire",
        "Take one tilting scan with a URG-04LX (SCIP 2.0) and a DYNAMIXEL tilt servo, or their "
        "emulation (--emulate), and write it as a raw scan");
    auto args = std::make_shared<AcquireSettings>();
    args->add_to(*cmd);
    cmd->add_flag("-q,--quiet", args->quiet, "No summary line on stdout");
    cmd->callback([args] {
        const AcquiredScan t = take_scan(*args);
        if (args->quiet) return;
        char buf[320];
        std::snprintf(buf, sizeof buf,
                      "%s: %d tilt positions x %d steps x %d readings in %.1f s (%d retries)%s",
                      t.file.string().c_str(), t.scan.spec.tilt.positions,
                      t.scan.spec.laser.steps(), t.scan.spec.readings_per_ray, t.seconds, t.retries,
                      args->emulate.empty() ? "" : ", emulated");
        std::cout << buf << std::endl;
    });
}

}  // namespace surfgrow::cli
