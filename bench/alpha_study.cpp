// The study behind the default alpha (docs/algorithm.md): how often the plane test of eq. (2)
// accepts neighbourhoods of noisy planes, and of 90-degree edges by distance from the edge.
// Run: build/bench/alpha_study
#include <cstdio>
#include <random>
#include <vector>
#include "surfgrow/core/plane_fit.hpp"
using namespace surfgrow;
int main() {
    const double mu = 0.012, s = 0.005;  // 12 mm, 5 mm spacing (URG at 1 m)
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> jit(-0.3 * s, 0.3 * s);
    // Ratio lambda_mid / lambda_min for neighbourhoods of a grid-sampled noisy plane.
    auto plane_ratios = [&](double sigma, double spacing) {
        std::normal_distribution<double> g(0, sigma);
        std::vector<double> ratios;
        for (int t = 0; t < 4000; ++t) {
            Moments m;
            const double ox = std::uniform_real_distribution<double>(0, spacing)(rng),
                         oy = std::uniform_real_distribution<double>(0, spacing)(rng);
            for (double x = -0.03 + ox; x < 0.03; x += spacing)
                for (double y = -0.03 + oy; y < 0.03; y += spacing) {
                    const Vec3d p(x + jit(rng) * spacing / s, y + jit(rng) * spacing / s, g(rng));
                    if (p.head<2>().norm() <= mu) m.add(p);
                }
            if (m.n < 10) continue;
            const PlaneFit f = fit_plane(m);
            ratios.push_back(f.eigenvalues[1] / std::max(f.eigenvalues[0], 1e-30));
        }
        return ratios;
    };
    // Edge: two faces meeting at 90 degrees along the y axis (z=0 plane for x<0, x=0 plane for
    // z>0), home point on the z=0 face at distance d from the edge.
    auto edge = [&](double sigma, double d, double alpha, double& accepted, double& err_deg) {
        std::normal_distribution<double> g(0, sigma);
        int acc = 0, n = 0;
        double err = 0;
        for (int t = 0; t < 1000; ++t) {
            Moments m;
            const Vec3d home(-d, 0, 0);
            const double o = std::uniform_real_distribution<double>(0, s)(rng);
            for (double a = -0.04 + o; a < 0.04; a += s)
                for (double b = -0.04 + o; b < 0.04; b += s) {
                    if (a < 0) {
                        const Vec3d p(a + jit(rng), b + jit(rng), g(rng));
                        if ((p - home).norm() <= mu) m.add(p - home);
                    } else {
                        const Vec3d p(g(rng), b + jit(rng), a + jit(rng));
                        if ((p - home).norm() <= mu) m.add(p - home);
                    }
                }
            if (m.n < 10) continue;
            ++n;
            const PlaneFit f = fit_plane(m);
            if (is_planar(f.eigenvalues, alpha)) {
                ++acc;
                err += axis_angle_between(f.normal, Vec3d::UnitZ());
            }
        }
        accepted = double(acc) / n;
        err_deg = acc ? err / acc * 180 / M_PI : 0;
    };
    printf("PLANES: fraction of neighbourhoods accepted (mu 12 mm, 5 mm spacing)\n sigma_mm ");
    const double alphas[] = {2, 3, 4, 6, 8, 12, 16, 25};
    for (double a : alphas) printf(" a=%-5g", a);
    printf("\n");
    for (double sigma_mm : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0}) {
        auto r = plane_ratios(sigma_mm / 1000, s);
        printf(" %5.1f    ", sigma_mm);
        for (double a : alphas) {
            int ok = 0;
            for (double x : r) ok += x > a;
            printf(" %6.4f", double(ok) / r.size());
        }
        printf("\n");
    }
    printf(
        "\nEDGES (90 deg): accepted fraction / mean normal error (deg) of accepted, by home "
        "distance to the edge\n");
    for (double sigma_mm : {1.0, 2.0}) {
        printf(" sigma %.1f mm\n  d_mm  ", sigma_mm);
        for (double a : alphas) printf("   a=%-9g", a);
        printf("\n");
        for (double d_mm : {0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0}) {
            printf("  %4.0f  ", d_mm);
            for (double a : alphas) {
                double acc, err;
                edge(sigma_mm / 1000, d_mm / 1000, a, acc, err);
                printf("  %4.2f/%5.1f  ", acc, err);
            }
            printf("\n");
        }
    }
}
