#include "surfgrow/eval/report_text.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace surfgrow::eval {

namespace {

// printf into a std::string (one piece of a line).
[[gnu::format(printf, 1, 2)]] std::string fmt(const char* format, ...) {
    char buf[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    return buf;
}

// "99.2%", or "n/a" when there is nothing to count.
std::string pct(double fraction) {
    return std::isfinite(fraction) ? fmt("%.1f%%", 100.0 * fraction) : std::string("n/a");
}

std::string deg(double v) {
    return std::isfinite(v) ? fmt("%.2f deg", v) : std::string("n/a");
}

std::string mm(double metres) {
    return std::isfinite(metres) ? fmt("%.2f mm", 1000.0 * metres) : std::string("n/a");
}

std::string share(const Share& s) {
    return pct(s.fraction()) + " of " + std::to_string(s.points);
}

}  // namespace

std::string eval_line(const EvalReport& r) {
    std::string line =
        "eval: " + pct(r.all.fraction()) + " registered (planar " + pct(r.planar.fraction());
    if (r.range_known)
        line += ", planar within " + fmt("%g m ", r.options.workspace_m) +
                pct(r.planar_workspace.fraction());
    line += "), normal error median " + deg(r.normal_deg.median) + " p95 " + deg(r.normal_deg.p95) +
            ", " + pct(r.normal_over_45) + " > 45 deg";
    if (r.planes.known)
        line += " (bound planes: p95 " + deg(r.planes.normal_deg.p95) + ", " +
                pct(r.planes.over_45) + " > 45 deg, " + std::to_string(r.planes.faces_detected) +
                "/" + std::to_string(r.planes.faces_scored) + " faces)";
    if (r.range_known) line += ", facing sensor " + pct(r.facing_sensor.fraction());
    line += ", purity " + pct(r.purity);
    return line;
}

std::string bands_line(const EvalReport& r) {
    if (r.bands.empty()) return {};
    std::string line = "range bands (planar registered, normal median):";
    for (const BandReport& b : r.bands) {
        if (b.planar.points == 0) continue;
        line += std::isfinite(b.to_m) ? fmt(" %.1f-%.1f m ", b.from_m, b.to_m)
                                      : fmt(" >= %.1f m ", b.from_m);
        line += pct(b.planar.fraction()) + " " + deg(b.normal_deg.median) + ",";
    }
    line.pop_back();
    return line;
}

std::string summary_text(const EvalReport& r) {
    std::string t;
    t += "registered       " + share(r.all) +
         " finite points (paper's loop alone: " + pct(r.registered_grown) + ")\n";
    t += "  planar faces   " + share(r.planar);
    if (r.range_known)
        t += fmt(", within %g m of the scanner: ", r.options.workspace_m) +
             share(r.planar_workspace);
    t += "\n  cylinder sides " + share(r.curved) + "\n";
    t += "  on no face     " + share(r.unlabelled) + " (mixed pixels)\n";
    t += "normal error     planar: median " + deg(r.normal_deg.median) + ", p95 " +
         deg(r.normal_deg.p95) + ", mean " + deg(r.normal_deg.mean);
    if (r.range_known)
        t += fmt("; within %g m: median ", r.options.workspace_m) +
             deg(r.normal_workspace_deg.median) + ", p95 " + deg(r.normal_workspace_deg.p95);
    t += "\n  cylinders      median " + deg(r.normal_curved_deg.median) + ", p95 " +
         deg(r.normal_curved_deg.p95) + "\n";
    if (r.range_known) t += "  facing sensor  " + share(r.facing_sensor) + " checked\n";
    t += "surfaces         " + std::to_string(r.surfaces) +
         fmt(" (%.1fx reduction)", r.data_reduction) + ", purity " + pct(r.purity) +
         " (per surface " + pct(r.purity_surface_mean) + ", " + std::to_string(r.impure_surfaces) +
         fmt(" below %.0f%%)\n", 100.0 * r.options.impure_below);
    t += "  vs their face  normal median " + deg(r.surface_normal_deg.median) + ", p95 " +
         deg(r.surface_normal_deg.p95) + "; plane offset median " + mm(r.plane_offset_m.median) +
         ", p95 " + mm(r.plane_offset_m.p95) + "\n";
    t += "  residual       mean " + mm(r.residual_m.mean) + ", p95 " + mm(r.residual_m.p95) + "\n";
    t += "faces            " + std::to_string(r.faces_grown) + " of " +
         std::to_string(r.faces_with_points) + " seen have surfaces" +
         fmt(" (%.1f each), ", r.surfaces_per_face) + std::to_string(r.faces_missed) +
         fmt(" with >= %llu points have none\n",
             static_cast<unsigned long long>(r.options.min_face_points));
    auto band_table = [&](const std::vector<BandReport>& bands, bool registration) {
        t += registration ? "range band      points  registered  planar reg.  normal median    "
                            "p95   > 10 deg  > 45 deg\n"
                          : "range band     normal median    p95   > 10 deg  > 45 deg\n";
        for (const BandReport& b : bands) {
            if (b.all.points == 0) continue;
            const std::string band = std::isfinite(b.to_m) ? fmt("%.1f-%.1f m", b.from_m, b.to_m)
                                                           : fmt(">= %.1f m", b.from_m);
            if (registration)
                t += fmt("%-12s %9llu %11s %12s", band.c_str(),
                         static_cast<unsigned long long>(b.all.points),
                         pct(b.all.fraction()).c_str(), pct(b.planar.fraction()).c_str());
            else
                t += fmt("%-12s", band.c_str());
            t += fmt(" %14s %10s %10s %9s\n", deg(b.normal_deg.median).c_str(),
                     deg(b.normal_deg.p95).c_str(), pct(b.over_10).c_str(), pct(b.over_45).c_str());
        }
    };
    auto incidence_table = [&](const std::vector<IncidenceReport>& bands) {
        t += "incidence      planar pts  planar reg.  normal median    p95   > 10 deg  > 45 deg\n";
        for (const IncidenceReport& b : bands) {
            if (b.planar.points == 0) continue;
            t += fmt("%2.0f-%2.0f deg %14llu %12s %14s %10s %10s %9s\n", b.from_deg, b.to_deg,
                     static_cast<unsigned long long>(b.planar.points),
                     pct(b.planar.fraction()).c_str(), deg(b.normal_deg.median).c_str(),
                     deg(b.normal_deg.p95).c_str(), pct(b.over_10).c_str(), pct(b.over_45).c_str());
        }
    };
    t += "normal tail      planar: " + pct(r.normal_over_10) + " > 10 deg, " +
         pct(r.normal_over_45) + " > 45 deg\n";
    if (!r.bands.empty()) band_table(r.bands, true);
    if (!r.incidence.empty()) incidence_table(r.incidence);
    if (r.planes.known) {
        t += "bound planes     each point judged by its bound plane (planes.json): median " +
             deg(r.planes.normal_deg.median) + ", p95 " + deg(r.planes.normal_deg.p95) + ", " +
             pct(r.planes.over_10) + " > 10 deg, " + pct(r.planes.over_45) + " > 45 deg\n";
        t += "  faces detected " + std::to_string(r.planes.faces_detected) + " of " +
             std::to_string(r.planes.faces_scored) +
             " planar faces with >= 500 points (SegComp, T = 0.8)\n";
        if (!r.planes.bands.empty()) band_table(r.planes.bands, false);
        if (!r.planes.incidence.empty()) incidence_table(r.planes.incidence);
    }
    return t;
}

std::string requirements_text(const std::vector<RequirementCheck>& checks) {
    std::string t;
    for (const RequirementCheck& c : checks)
        t += "require " + c.requirement.text + ": " +
             (std::isfinite(c.value) ? fmt("%.6g", c.value) : std::string("n/a")) +
             (c.met ? " ok\n" : " FAILED\n");
    return t;
}

}  // namespace surfgrow::eval
