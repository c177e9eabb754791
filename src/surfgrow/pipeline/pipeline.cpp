#include "surfgrow/pipeline/pipeline.hpp"

#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"

namespace surfgrow {

Pipeline::Pipeline(PipelineConfig config) : config_(std::move(config)) {
    validate(config_.grow);
    if (config_.planes) {
        config_.planes->mu = config_.grow.mu;
        config_.planes->threads = config_.grow.threads;
        validate(*config_.planes);
    }
    if (config_.coverage) {
        config_.coverage->threads = config_.grow.threads;
        validate(*config_.coverage);
    }
}

PipelineResult Pipeline::run(const CloudView& cloud) const {
    const SurfaceGrower grower(config_.grow);
    // The index is kept for the occupancy grid, which lies on exactly the grower's cubes.
    std::optional<GrowIndex> index = grower.index(cloud);
    GrowResult grown = grower.grow(cloud, *index);
    if (!config_.occupancy) index.reset();
    return outputs(cloud, std::move(grown), std::move(index));
}

PipelineResult Pipeline::finish(const CloudView& cloud, GrowResult grown) const {
    if (grown.labels.size() != cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"pipeline: ", std::to_string(grown.labels.size()), " labels for ",
                         std::to_string(cloud.size()), " points"}));
    std::optional<GrowIndex> index;
    if (config_.occupancy) index = SurfaceGrower(config_.grow).index(cloud);
    return outputs(cloud, std::move(grown), std::move(index));
}

PipelineResult Pipeline::outputs(const CloudView& cloud, GrowResult grown,
                                 std::optional<GrowIndex> index) const {
    const PipelineConfig& c = config_;
    const auto report = [&](std::string_view stage) {
        if (c.grow.progress) c.grow.progress(stage, 1.0);
    };
    PipelineResult r;
    r.grow = std::move(grown);

    if (c.planes) {
        const Stopwatch watch;
        r.planes = compute_bound_planes(cloud, r.grow.surfaces, r.grow.labels, *c.planes);
        r.seconds.planes = watch.seconds();
        report("planes");
        if (c.coverage) {
            const Stopwatch cover;
            r.coverage = plan_coverage(*r.planes, r.grow.surfaces, *c.coverage);
            r.seconds.coverage = cover.seconds();
            report("coverage");
        }
    }
    if (c.occupancy) {
        const Stopwatch watch;
        r.occupancy = OccupancyGrid(index->index, r.grow.labels, c.grow.mu);
        index.reset();
        r.seconds.occupancy = watch.seconds();
        report("occupancy");
    }
    if (c.collision) {
        const Stopwatch watch;
        r.collision = CollisionSpheres::from_surfaces(r.grow.surfaces);
        r.seconds.collision = watch.seconds();
        report("collision");
    }
    report("done");
    return r;
}

}  // namespace surfgrow
