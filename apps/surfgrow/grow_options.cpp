#include "grow_options.hpp"

#include "cli_common.hpp"
#include "surfgrow/core/error.hpp"

namespace surfgrow::cli {

void GrowOptions::add_to(CLI::App& cmd) {
    cmd.add_option("--mu", mu, "Cube side and neighbourhood radius, with unit (paper: 12mm)")
        ->capture_default_str();
    cmd.add_option("--min-pts", min_pts, "Fewest neighbours within mu for a plane (paper: 10)")
        ->capture_default_str();
    cmd.add_option("--alpha", alpha, "Plane test: min(lambda) < mid(lambda)/alpha, alpha > 1")
        ->capture_default_str();
    cmd.add_option("--plane-test", plane_test,
                   "disk: eq. (2), and the points must span the ball and face the sensor, with "
                   "best-fit registration within a noise-tied tolerance; paper: eq. (2) alone, "
                   "first come, tolerance mu")
        ->capture_default_str();
    cmd.add_option("--min-spread", min_spread,
                   "Disk test: mid(lambda) must reach this share of a disk's r^2/4")
        ->capture_default_str();
    cmd.add_option("--max-incidence", max_incidence,
                   "Disk test: largest angle between a normal and the line of sight, degrees")
        ->capture_default_str();
    cmd.add_option("--noise-sigmas", noise_sigmas,
                   "Disk test: register points within this many noise sigmas of the plane")
        ->capture_default_str();
    cmd.add_option("--plane-tol", plane_tol,
                   "Register points within this distance of the plane, per mu of radius "
                   "(default: noise-tied; mu with --plane-test paper)");
    cmd.add_option(
        "--mu-max", mu_max,
        "Adaptive radius: double mu where points are too sparse or not yet a plane, up to this "
        "length, or off (default: 8 mu)");
    cmd.add_option("--min-new", min_new,
                   "A new surface must take at least this many unregistered points")
        ->capture_default_str();
    cmd.add_option("--pool-angle", pool_angle,
                   "Refine normals over adjacent surfaces within this angle, degrees (0: off)")
        ->capture_default_str();
    cmd.add_flag("--no-attach", no_attach,
                 "Skip the leftover pass and strips (the paper's loop alone)");
    add_seed_option(cmd, seed, "Random seed for home points (same seed, same output)");
    add_threads_option(cmd, threads,
                       "Worker threads, 0 = all cores (output does not depend on it)");
    cmd.add_option("--units", cloud_units, "Length unit of the input cloud: m, cm or mm")
        ->capture_default_str();
    cmd.add_option("--viewpoint", viewpoint,
                   "Sensor position x,y,z with unit (e.g. 0,0,1.2m) for normals");
    cmd.add_option("--crop-box", crop_box, "Workspace box xmin,ymin,zmin,xmax,ymax,zmax with unit");
    cmd.add_option("--crop-radius", crop_radius,
                   "Workspace radius around --crop-center (default: the viewpoint)");
    cmd.add_option("--crop-center", crop_center, "Centre x,y,z with unit of --crop-radius");
    cmd.add_option("--range-band", range_band, "Width of the range bands in the statistics")
        ->capture_default_str();
}

CloudUnits GrowOptions::units() const {
    return {cloud_units, unit_to_metres(cloud_units, "--units")};
}

GrowerConfig GrowOptions::config(const CloudUnits& u) const {
    auto len = [&](const std::string& text, const char* option) {
        return parse_length_m(text, option) / u.metres;
    };
    auto vec = [&](const std::string& text, const char* option) -> Vec3d {
        return parse_vec3_length_m(text, option) / u.metres;
    };
    GrowerConfig c;
    c.mu = len(mu, "--mu");
    c.min_pts = min_pts;
    c.alpha = alpha;
    if (plane_test == "disk")
        c.plane_test = PlaneTest::kDisk;
    else if (plane_test == "paper")
        c.plane_test = PlaneTest::kPaper;
    else
        throw Error(ErrorCode::kUsage,
                    "--plane-test: unknown test '" + plane_test + "' (use disk or paper)");
    c.min_spread = min_spread;
    c.max_incidence_deg = max_incidence;
    c.noise_sigmas = noise_sigmas;
    if (!plane_tol.empty()) c.plane_tolerance = len(plane_tol, "--plane-tol");
    if (mu_max == "off")
        c.adaptive_factor = 1.0;
    else if (!mu_max.empty())
        c.adaptive_factor = len(mu_max, "--mu-max") / c.mu;
    c.min_new_points = min_new;
    c.pool_angle_deg = pool_angle;
    c.attach_leftovers = !no_attach;
    c.seed = seed;
    c.threads = threads;
    if (!viewpoint.empty()) c.viewpoint = vec(viewpoint, "--viewpoint");
    if (!crop_box.empty()) {
        const std::vector<double> b = parse_lengths_m(crop_box, "--crop-box", 6);
        Aabb box;
        box.min = Vec3d(b[0], b[1], b[2]) / u.metres;
        box.max = Vec3d(b[3], b[4], b[5]) / u.metres;
        c.crop.box = box;
    }
    if (!crop_radius.empty()) c.crop.radius = len(crop_radius, "--crop-radius");
    if (!crop_center.empty()) {
        if (crop_radius.empty())
            throw Error(ErrorCode::kUsage, "--crop-center needs --crop-radius");
        c.crop.center = vec(crop_center, "--crop-center");
    }
    c.range_band = len(range_band, "--range-band");
    validate(c);
    return c;
}

}  // namespace surfgrow::cli
