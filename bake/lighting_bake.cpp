#include "bake/lighting_bake.h"

#include "bake/parallel_jobs.h"
#include "bake/ray_caster.h"
#include "bake/sampling.h"
#include "core/error.h"
#include "core/sh.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <utility>

namespace tetprobe {

namespace {

using Rgb = std::array<double, 3>;

double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Light arriving at x from a delta light: the direction toward the light, the distance to it
// (infinity for a directional light) and the irradiance on a surface facing it. False if none.
bool light_arrival(const Light& light, const double local_position[3], const double x[3], double to_light[3],
                   double* distance, Rgb* irradiance) {
    double scale = light.intensity;
    if (light.type == LightType::directional) {
        for (int a = 0; a < 3; ++a) to_light[a] = -light.direction[a];
        *distance = INFINITY;
    } else {
        double d[3] = {local_position[0] - x[0], local_position[1] - x[1], local_position[2] - x[2]};
        double length = std::sqrt(dot3(d, d));
        if (!(length > 0.0) || length > light.range) return false;
        for (int a = 0; a < 3; ++a) to_light[a] = d[a] / length;
        *distance = length;
        const double falloff = std::max(length, light.near_distance);  // bounded near the light
        scale /= falloff * falloff;
        if (light.type == LightType::spot) {
            double c = -dot3(to_light, light.direction.data());  // cosine from the spot's axis
            if (c <= light.cos_outer) return false;
            if (c < light.cos_inner) {
                double t = (c - light.cos_outer) / (light.cos_inner - light.cos_outer);
                scale *= t * t * (3.0 - 2.0 * t);
            }
        }
    }
    if (!(scale > 0.0)) return false;
    for (int c = 0; c < 3; ++c) (*irradiance)[c] = light.color[c] * scale;
    return (*irradiance)[0] > 0 || (*irradiance)[1] > 0 || (*irradiance)[2] > 0;
}

// The power heuristic weight (exponent 2) of a sample drawn with density `chosen` when another
// strategy would have drawn it with density `other` (Veach's multiple importance sampling).
double power_heuristic(double chosen, double other) {
    if (std::isinf(chosen)) return 1.0;
    const double a = chosen * chosen, b = other * other;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

// Sampling dimensions of ray `ray` of a probe: 0 and 1 place the probe's own direction, the
// continuation after reflection r uses 2 + 2r and 3 + 2r, the emitter point drawn at that
// reflection the two from emitter_dimension(r), and the emitter point drawn from the probe itself
// the two from kProbeEmitterDimension; all far apart.
uint64_t emitter_dimension(uint32_t reflection) { return (uint64_t(1) << 32) + 2 * uint64_t(reflection); }
constexpr uint64_t kProbeEmitterDimension = uint64_t(1) << 33;

// Density per unit solid angle of the probe's own ray directions, uniform over the sphere.
constexpr double kSpherePdf = 1.0 / (4.0 * kPi);

// An emissive triangle for next-event estimation, in local coordinates.
struct Emitter {
    double corner[3], edge1[3], edge2[3];
    double normal[3];  // unit, the side that emits when one-sided
    const Material* material;
    double area_pdf;   // density per unit area of drawing a point on it: P(triangle) / area
};

class Baker {
public:
    Baker(const Scene& scene, const std::vector<float>& positions, const BakeSettings& settings,
          const EffectsPlan& plan)
        : scene_(scene), settings_(settings), plan_(plan) {
        const size_t count = positions.size() / 3;
        for (size_t i = 0; i < positions.size(); ++i) origin_[i % 3] += double(positions[i]) / double(count);
        caster_ = std::make_unique<RayCaster>(scene, origin_);
        probes_.resize(positions.size());
        for (size_t i = 0; i < positions.size(); ++i) probes_[i] = double(positions[i]) - origin_[i % 3];

        // Offsets of ray origins off surfaces: relative to the extent of everything traced.
        double extent = 0.0;
        for (double p : probes_) extent = std::max(extent, std::abs(p));
        for (const Mesh& mesh : scene.meshes())
            for (int a = 0; a < 3; ++a)
                extent = std::max({extent, std::abs(mesh.bounds_min[a] - origin_[a]),
                                   std::abs(mesh.bounds_max[a] - origin_[a])});
        epsilon_ = 1e-5 * std::max(extent, 1e-6);

        for (const Light& light : scene.lights()) {
            std::array<double, 3> p{};
            for (int a = 0; a < 3; ++a) p[a] = light.position[a] - origin_[a];
            light_positions_.push_back(p);
        }
        occlusion_set_.assign(scene.lights().size(), -1);
        for (uint32_t l : plan.direct_lights)
            if (settings.culling && scene.lights()[l].shadows && !scene.meshes().empty())
                occlusion_set_[l] = int(caster_->add_occlusion_set(plan.occluders[l]));

        for (size_t m = 0; m < scene.meshes().size(); ++m) {
            const Mesh& mesh = scene.meshes()[m];
            const std::vector<float>& v = caster_->local_vertices(uint32_t(m));
            std::vector<float> normals(mesh.indices.size());
            for (size_t t = 0; t < mesh.triangle_count(); ++t) {
                const uint32_t* tri = &mesh.indices[3 * t];
                double e1[3], e2[3];
                for (int a = 0; a < 3; ++a) {
                    e1[a] = double(v[3 * tri[1] + a]) - v[3 * tri[0] + a];
                    e2[a] = double(v[3 * tri[2] + a]) - v[3 * tri[0] + a];
                }
                double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
                double length = std::sqrt(dot3(n, n));
                for (int a = 0; a < 3; ++a) normals[3 * t + a] = float(length > 0 ? n[a] / length : 0.0);
            }
            normals_.push_back(std::move(normals));
        }
        if (settings.emitter_sampling) build_emitters();
    }

    // The 27 SH floats of probe i; `rays` counts the rays traced.
    void bake_probe(size_t i, float out[27], uint64_t* rays) const {
        const double* x = &probes_[3 * i];
        double sh[27] = {};
        if (plan_.sampled()) sample_sphere(i, x, sh, rays);

        // Delta lights: radiance arriving from direction w projects onto E * Y(w).
        for (uint32_t l : plan_.direct_lights) {
            const Light& light = scene_.lights()[l];
            double w[3], distance;
            Rgb e;
            if (!light_arrival(light, light_positions_[l].data(), x, w, &distance, &e)) continue;
            if (light.shadows && !scene_.meshes().empty()) {
                ++*rays;
                if (occluded(x, w, distance, occlusion_set_[l])) continue;
            }
            double basis[9];
            sh_basis(w[0], w[1], w[2], basis);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 9; ++k) sh[9 * c + k] += e[c] * basis[k];
        }
        for (int k = 0; k < 27; ++k) out[k] = float(sh[k]);
    }

    const RayCaster& caster() const { return *caster_; }

private:
    bool occluded(const double x[3], const double w[3], double distance, int set) const {
        float o[3] = {float(x[0]), float(x[1]), float(x[2])}, d[3] = {float(w[0]), float(w[1]), float(w[2])};
        float far = std::isinf(distance) ? INFINITY : float(distance - epsilon_);
        if (!(far > 0.0f)) return false;
        return caster_->occluded(o, d, 0.0f, far, set);
    }

    // Radiance of the sky arriving from direction w.
    Rgb sky_radiance(const double w[3]) const {
        Rgb l{0, 0, 0};
        if (!plan_.sky) return l;
        double basis[9];
        sh_basis(w[0], w[1], w[2], basis);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 9; ++k) l[c] += scene_.sky().sh[9 * c + k] * basis[k];
        return l;
    }

    // Emissive triangles, chosen in proportion to the power they emit (area x mean emitted radiance
    // x sides), so a small bright panel gets its share of the samples however large the dim
    // surfaces around it; the cumulative distribution is searched with one uniform.
    void build_emitters() {
        area_pdf_.resize(scene_.meshes().size());
        std::vector<std::pair<uint32_t, uint32_t>> triangles;  // (mesh, triangle) per emitter
        std::vector<double> areas, power;
        for (uint32_t m : plan_.emissive_meshes) {
            const Mesh& mesh = scene_.meshes()[m];
            const std::vector<float>& v = caster_->local_vertices(m);
            area_pdf_[m].assign(mesh.triangle_count(), 0.0);
            for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
                const Material& material = mesh.materials[mesh.triangle_materials[t]];
                if (!material.emissive()) continue;
                const uint32_t* tri = &mesh.indices[3 * t];
                Emitter e;
                for (int a = 0; a < 3; ++a) {
                    e.corner[a] = v[3 * tri[0] + a];
                    e.edge1[a] = double(v[3 * tri[1] + a]) - e.corner[a];
                    e.edge2[a] = double(v[3 * tri[2] + a]) - e.corner[a];
                    e.normal[a] = normals_[m][3 * t + a];
                }
                const double c[3] = {e.edge1[1] * e.edge2[2] - e.edge1[2] * e.edge2[1],
                                     e.edge1[2] * e.edge2[0] - e.edge1[0] * e.edge2[2],
                                     e.edge1[0] * e.edge2[1] - e.edge1[1] * e.edge2[0]};
                const double area = 0.5 * std::sqrt(dot3(c, c));
                if (!(area > 0.0)) continue;  // degenerate in local floats: nothing can hit it either
                const double radiance = (double(material.emission[0]) + material.emission[1] + material.emission[2]) / 3.0;
                e.material = &material;
                emitters_.push_back(e);
                triangles.push_back({m, t});
                areas.push_back(area);
                power.push_back(area * radiance * (material.two_sided ? 2.0 : 1.0));
            }
        }
        double total = 0.0;
        for (double p : power) total += p;
        if (!(total > 0.0)) {
            emitters_.clear();
            return;
        }
        double running = 0.0;
        for (size_t k = 0; k < emitters_.size(); ++k) {
            running += power[k];
            emitter_cdf_.push_back(running / total);
            emitters_[k].area_pdf = power[k] / total / areas[k];
            area_pdf_[triangles[k].first][triangles[k].second] = emitters_[k].area_pdf;
        }
        emitter_cdf_.back() = 1.0;
    }

    // The density per unit area with which next-event estimation picks a point on this triangle.
    double emitter_area_pdf(uint32_t mesh, uint32_t triangle) const {
        return emitters_.empty() || area_pdf_[mesh].empty() ? 0.0 : area_pdf_[mesh][triangle];
    }

    // One point drawn on the emitters from two uniforms, seen from x: u0 chooses an emitter by
    // power and, rescaled within that emitter's share, places the point with u1 (so stratified
    // uniforms stay stratified on each emitter). Gives the unit direction from x to the point, its
    // distance, the emitter, and the density per unit solid angle at x; false when the emitting side
    // faces away from x or the point is degenerate. Casts no ray.
    bool draw_emitter_point(double u0, double u1, const double x[3], double to_point[3], double* distance,
                            const Emitter** emitter, double* light_pdf) const {
        const size_t k = std::min(size_t(std::upper_bound(emitter_cdf_.begin(), emitter_cdf_.end(), u0) -
                                         emitter_cdf_.begin()),
                                  emitters_.size() - 1);
        const double low = k > 0 ? emitter_cdf_[k - 1] : 0.0, share = emitter_cdf_[k] - low;
        const double v = share > 0.0 ? std::min(std::max((u0 - low) / share, 0.0), 1.0) : 0.5;
        const Emitter& e = emitters_[k];
        double weights[3];
        uniform_triangle_weights(v, u1, weights);
        for (int a = 0; a < 3; ++a)
            to_point[a] = e.corner[a] + weights[1] * e.edge1[a] + weights[2] * e.edge2[a] - x[a];
        const double distance2 = dot3(to_point, to_point);
        *distance = std::sqrt(distance2);
        if (!(*distance > 0.0)) return false;
        for (int a = 0; a < 3; ++a) to_point[a] /= *distance;
        double cos_emitter = -dot3(e.normal, to_point);
        if (e.material->two_sided) cos_emitter = std::abs(cos_emitter);
        if (!(cos_emitter > 0.0)) return false;
        *emitter = &e;
        *light_pdf = e.area_pdf * distance2 / cos_emitter;
        return true;
    }

    // Next-event estimation of the emissive triangles at surface point p with unit normal n (on the
    // side the path arrived from): one point drawn on the emitters, a shadow ray to it, weighted by
    // the power heuristic against the cosine-sampled continuation finding the same point. Returns
    // the reflected radiance per unit albedo.
    Rgb emitter_light(uint64_t probe, uint32_t ray, uint32_t reflection, const double p[3], const double n[3],
                      uint64_t* rays) const {
        Rgb light{0, 0, 0};
        const uint64_t dimension = emitter_dimension(reflection);
        double to_point[3], distance, light_pdf;
        const Emitter* e;
        if (!draw_emitter_point(sample_uniform(settings_.seed, probe, ray, dimension),
                                sample_uniform(settings_.seed, probe, ray, dimension + 1), p, to_point, &distance, &e,
                                &light_pdf))
            return light;
        const double cos_surface = dot3(n, to_point);
        if (cos_surface <= 0.0) return light;
        ++*rays;
        if (occluded(p, to_point, distance, -1)) return light;
        const double scale = cos_surface / kPi / light_pdf * power_heuristic(light_pdf, cos_surface / kPi);
        for (int c = 0; c < 3; ++c) light[c] = e->material->emission[c] * scale;
        return light;
    }

    // Emission arriving at probe x straight from the emitters, estimated from point `ray` of `rays`
    // drawn on them (stratified like the probe's own directions) and weighted by the power heuristic
    // against the probe's uniform directions finding the same point; adds the radiance times the
    // SH basis over the density to `sum`.
    void probe_emitter_sample(uint64_t probe, uint32_t ray, uint32_t rays_per_probe, const double x[3],
                              Eigen::Matrix<double, 9, 3>& sum, uint64_t* rays) const {
        const double jitter = sample_uniform(settings_.seed, probe, ray, kProbeEmitterDimension);
        const double rotation = sample_uniform(settings_.seed, probe, 0xffffffffull, kProbeEmitterDimension + 1);
        const double u0 = (double(ray) + jitter) / double(rays_per_probe);
        const double turn = double(ray) * 0.6180339887498949 + rotation;
        double to_point[3], distance, light_pdf;
        const Emitter* e;
        if (!draw_emitter_point(u0, turn - std::floor(turn), x, to_point, &distance, &e, &light_pdf)) return;
        ++*rays;
        if (occluded(x, to_point, distance, -1)) return;
        Eigen::Matrix<double, 9, 1> basis;
        sh_basis(to_point[0], to_point[1], to_point[2], basis.data());
        const double scale = power_heuristic(light_pdf, kSpherePdf) / light_pdf;
        for (int c = 0; c < 3; ++c) sum.col(c) += (e->material->emission[c] * scale) * basis;
    }

    // Radiance arriving at x from direction w: sky at the end of a path; lights and emitters by
    // next-event estimation at each reflection, up to the plan's bounces; emission where a segment
    // ends on an emitter, weighted against the emitter points drawn from the probe (first segment)
    // or from the reflection it left (later ones).
    Rgb trace(uint64_t probe, uint32_t ray, const double x[3], const double w[3], uint64_t* rays) const {
        Rgb radiance{0, 0, 0}, throughput{1, 1, 1};
        double origin[3] = {x[0], x[1], x[2]}, direction[3] = {w[0], w[1], w[2]};
        double continuation_pdf = 0;  // solid-angle density of the last reflection's direction
        for (uint32_t reflections = 0;; ++reflections) {
            float o[3] = {float(origin[0]), float(origin[1]), float(origin[2])};
            float d[3] = {float(direction[0]), float(direction[1]), float(direction[2])};
            RayHit hit;
            ++*rays;
            if (!caster_->intersect(o, d, 0.0f, INFINITY, &hit)) {
                Rgb sky = sky_radiance(direction);
                for (int c = 0; c < 3; ++c) radiance[c] += throughput[c] * sky[c];
                break;
            }
            const Mesh& mesh = scene_.meshes()[hit.mesh];
            const Material& material = mesh.materials[mesh.triangle_materials[hit.triangle]];
            const float* ng = &normals_[hit.mesh][3 * hit.triangle];
            double n[3] = {ng[0], ng[1], ng[2]};
            const double cos_hit = -dot3(n, direction);
            if (cos_hit < 0.0) {
                if (!material.two_sided) break;  // the back of a one-sided surface is black
                for (double& c : n) c = -c;
            }
            if (material.emissive()) {
                double weight = 1.0;
                if (!emitters_.empty()) {
                    const double light_pdf = emitter_area_pdf(hit.mesh, hit.triangle) * double(hit.distance) *
                                             double(hit.distance) / std::abs(cos_hit);
                    weight = power_heuristic(reflections > 0 ? continuation_pdf : kSpherePdf, light_pdf);
                }
                for (int c = 0; c < 3; ++c) radiance[c] += throughput[c] * material.emission[c] * weight;
            }
            if (reflections >= plan_.bounces || !material.reflective()) break;

            double p[3];
            for (int a = 0; a < 3; ++a) p[a] = origin[a] + direction[a] * hit.distance + n[a] * epsilon_;
            for (uint32_t l : plan_.bounce_lights) {
                const Light& light = scene_.lights()[l];
                double to_light[3], distance;
                Rgb e;
                if (!light_arrival(light, light_positions_[l].data(), p, to_light, &distance, &e)) continue;
                double cosine = dot3(n, to_light);
                if (cosine <= 0.0) continue;
                if (light.shadows) {
                    ++*rays;
                    if (occluded(p, to_light, distance, -1)) continue;
                }
                for (int c = 0; c < 3; ++c)
                    radiance[c] += throughput[c] * material.albedo[c] / kPi * e[c] * cosine;
            }
            if (!emitters_.empty()) {
                const Rgb light = emitter_light(probe, ray, reflections, p, n, rays);
                for (int c = 0; c < 3; ++c) radiance[c] += throughput[c] * material.albedo[c] * light[c];
            }
            // Cosine-weighted continuation: the Lambertian weight albedo/pi * cos / pdf is the albedo.
            for (int c = 0; c < 3; ++c) throughput[c] *= material.albedo[c];
            const uint64_t dimension = 2 + 2 * uint64_t(reflections);
            cosine_direction(n, sample_uniform(settings_.seed, probe, ray, dimension),
                             sample_uniform(settings_.seed, probe, ray, dimension + 1), direction);
            continuation_pdf = std::max(0.0, dot3(n, direction)) / kPi;
            for (int a = 0; a < 3; ++a) origin[a] = p[a];
        }
        return radiance;
    }

    void sample_sphere(size_t probe, const double x[3], double sh[27], uint64_t* rays) const {
        const uint32_t n = settings_.rays;
        Eigen::Matrix<double, 9, 9> gram = Eigen::Matrix<double, 9, 9>::Zero();
        Eigen::Matrix<double, 9, 3> projection = Eigen::Matrix<double, 9, 3>::Zero();
        Eigen::Matrix<double, 9, 3> emitted = Eigen::Matrix<double, 9, 3>::Zero();  // from emitter points
        for (uint32_t r = 0; r < n; ++r) {
            if (!emitters_.empty()) probe_emitter_sample(probe, r, n, x, emitted, rays);
            double w[3];
            stratified_sphere_direction(settings_.seed, probe, r, n, w);
            Rgb l = trace(probe, r, x, w, rays);
            Eigen::Matrix<double, 9, 1> basis;
            sh_basis(w[0], w[1], w[2], basis.data());
            gram.noalias() += basis * basis.transpose();
            for (int c = 0; c < 3; ++c) projection.col(c) += l[c] * basis;
        }
        const double weight = 4.0 * kPi / double(n);
        gram *= weight;
        projection *= weight;
        // Least squares over the samples: the plain Monte Carlo projection corrected by the samples'
        // Gram matrix, which removes the quadrature error inside the L2 span.
        Eigen::Matrix<double, 9, 3> coefficients = projection;
        if (n >= 16) {
            Eigen::LDLT<Eigen::Matrix<double, 9, 9>> ldlt(gram);
            if (ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 1e-3)
                coefficients = ldlt.solve(projection);
        }
        // The emitter points' share is a plain Monte Carlo estimate of its own projection: their
        // directions are not the probe's, so the Gram correction does not apply to it.
        coefficients += emitted / double(n);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 9; ++k) sh[9 * c + k] += coefficients(k, c);
    }

    const Scene& scene_;
    const BakeSettings& settings_;
    const EffectsPlan& plan_;
    double origin_[3] = {0, 0, 0};
    std::unique_ptr<RayCaster> caster_;
    std::vector<double> probes_;  // local
    double epsilon_ = 0;
    std::vector<std::array<double, 3>> light_positions_;  // local
    std::vector<int> occlusion_set_;                      // per light, -1 = every mesh
    std::vector<std::vector<float>> normals_;             // per mesh, 3 per kept triangle, unit
    std::vector<Emitter> emitters_;                       // empty: no emitter sampling
    std::vector<double> emitter_cdf_;                     // cumulative power fraction per emitter
    std::vector<std::vector<double>> area_pdf_;           // per mesh, per triangle (empty: none emits)
};

}  // namespace

std::vector<float> bake_lighting(const Scene& scene, const std::vector<float>& positions,
                                 const BakeSettings& settings, EffectsPlan* plan_out, BakeStats* stats) {
    const size_t count = positions.size() / 3;
    if (count == 0) throw Error(Status::degenerate, "no probe positions to bake");
    if (scene.empty()) throw Error(Status::scene, "the scene is empty (no mesh, light or sky)");
    for (float p : positions)
        if (!std::isfinite(p)) throw Error(Status::invalid_argument, "a probe position is not finite");
    if (settings.rays == 0) throw Error(Status::invalid_argument, "rays must be at least 1");

    const EffectsPlan plan = derive_effects_plan(scene, positions, settings.bounces, settings.culling);
    if (plan_out) *plan_out = plan;
    const Baker baker(scene, positions, settings, plan);

    std::vector<float> sh(27 * count);
    std::atomic<uint64_t> rays{0};
    const auto start = std::chrono::steady_clock::now();
    run_jobs(count, settings.threads, [&](size_t i) {
        uint64_t traced = 0;
        baker.bake_probe(i, &sh[27 * i], &traced);
        rays.fetch_add(traced, std::memory_order_relaxed);
    }, settings.progress, "bake");
    if (stats) {
        stats->rays_cast = rays.load();
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return sh;
}

}  // namespace tetprobe
