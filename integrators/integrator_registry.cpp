#include <memory>

#include "integrators/ao_integrator.h"
#include "integrators/debug_integrators.h"
#include "integrators/direct_integrator.h"
#include "integrators/integrator.h"
#include "integrators/path_integrator.h"

namespace prism {

const Registry<Integrator>& integrator_registry() {
  using Entry = Registry<Integrator>::Entry;
  static const Registry<Integrator> registry(
      "integrator",
      {
          Entry{"path",
                "global illumination: path tracing with next-event estimation, MIS, Russian "
                "roulette (path.max_depth or -m, path.light_samples or -l, path.hemisphere or "
                "-H, path.mis, path.accumulate, path.rr, path.rr_depth, path.rr_probability, "
                "path.rr_sqrt, path.rr_threshold, path.caustics, path.caustic_paths, "
                "path.caustic_radius, path.caustic_connections, path.microfacet, "
                "path.ambient_visible, path.two_sided_emitters or --two-sided-emitters, "
                "path.rectangle_sampling)",
                [](const ParamSet& p) { return std::make_unique<PathIntegrator>(p); }},
          Entry{"direct",
                "zero plus one bounce: light importance sampling, or uniform hemisphere "
                "sampling (direct.light_samples or -l, direct.hemisphere or -H, "
                "direct.microfacet, direct.ambient_visible, direct.two_sided_emitters or "
                "--two-sided-emitters, direct.rectangle_sampling)",
                [](const ParamSet& p) { return std::make_unique<DirectIntegrator>(p); }},
          Entry{"ao", "ambient occlusion at the first hit (ao.samples, ao.max_distance)",
                [](const ParamSet& p) { return std::make_unique<AoIntegrator>(p); }},
          Entry{"normals",
                "shading normal n of the first hit as colour 0.5 n + 0.5; black background",
                [](const ParamSet&) { return std::make_unique<NormalsIntegrator>(); }},
          Entry{"depth", "distance to the first hit as grey; 0 where the ray escapes",
                [](const ParamSet&) { return std::make_unique<DepthIntegrator>(); }},
      });
  return registry;
}

}  // namespace prism
