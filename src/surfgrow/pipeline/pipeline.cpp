#include "surfgrow/pipeline/pipeline.hpp"

#include <future>
#include <string>

#include "surfgrow/core/error.hpp"
#include "surfgrow/core/stopwatch.hpp"
#include "surfgrow/core/text.hpp"
#include "surfgrow/core/threads.hpp"

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
    return outputs(cloud, std::move(grown), std::move(index), nullptr);
}

PipelineResult Pipeline::finish(const CloudView& cloud, const GrowResult& grown,
                                PipelineMemo* memo) const {
    GrowResult copy = grown;
    return finish(cloud, std::move(copy), memo);
}

PipelineResult Pipeline::finish(const CloudView& cloud, GrowResult&& grown,
                                PipelineMemo* memo) const {
    if (grown.labels.size() != cloud.size())
        throw Error(ErrorCode::kInvalidParameter,
                    cat({"pipeline: ", std::to_string(grown.labels.size()), " labels for ",
                         std::to_string(cloud.size()), " points"}));
    return outputs(cloud, std::move(grown), std::nullopt, memo);  // the occupancy grid indexes it
}

PipelineResult Pipeline::outputs(const CloudView& cloud, GrowResult&& grown,
                                 std::optional<GrowIndex> index, PipelineMemo* memo) const {
    const PipelineConfig& c = config_;
    const auto report = [&](std::string_view stage) {
        if (c.grow.progress) c.grow.progress(stage, 1.0);
    };
    PipelineResult r;  // takes `grown` over at the end: a stage that throws leaves it as it was

    // The occupancy grid (on the grower's cubes: indexed here when the caller has no index) and
    // the collision spheres need none of the planes. With more than one thread they are built
    // while the planes and coverage run, whose serial parts (growing the regions, the largest
    // plane's fit) leave a core idle: a Map's 2 M points take 0.05 s to index after a scan that
    // moves the grid's origin (after the others its grid is extended: OccupancyMemo). Each writes
    // only its own members of r.
    const auto occupancy_and_collision = [&] {
        if (c.occupancy) {
            const Stopwatch watch;
            if (memo) r.occupancy = extend_occupancy(memo->occupancy, cloud, grown.labels, c.grow);
            if (!r.occupancy) {
                if (!index) index = SurfaceGrower(c.grow).index(cloud);
                r.occupancy = OccupancyGrid(index->index, grown.labels, c.grow.mu);
                if (memo)
                    remember_occupancy(memo->occupancy, cloud, grown.labels, index->index.bounds(),
                                       *r.occupancy, c.grow);
            }
            index.reset();
            r.seconds.occupancy = watch.seconds();
        }
        if (c.collision) {
            const Stopwatch watch;
            r.collision = CollisionSpheres::from_surfaces(grown.surfaces);
            r.seconds.collision = watch.seconds();
        }
    };
    // If the planes throw, this future's destructor (std::async's) waits for the task, which
    // fills r, before r goes: it is declared after r.
    std::future<void> meanwhile;
    if ((c.occupancy || c.collision) && resolve_threads(c.grow.threads) > 1)
        meanwhile = std::async(std::launch::async, occupancy_and_collision);
    if (c.planes) {
        const Stopwatch watch;
        r.planes = compute_bound_planes(cloud, grown.surfaces, grown.labels, *c.planes,
                                        memo ? &memo->planes : nullptr);
        r.seconds.planes = watch.seconds();
        report("planes");
        if (c.coverage) {
            const Stopwatch cover;
            r.coverage = plan_coverage(*r.planes, grown.surfaces, *c.coverage,
                                       memo ? &memo->coverage : nullptr);
            r.seconds.coverage = cover.seconds();
            report("coverage");
        }
    }
    if (meanwhile.valid()) {
        meanwhile.get();  // rethrows what it threw
    } else {
        occupancy_and_collision();
    }
    r.grow = std::move(grown);
    if (c.occupancy) report("occupancy");
    if (c.collision) report("collision");
    report("done");
    return r;
}

}  // namespace surfgrow
