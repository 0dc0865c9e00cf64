#include "core/app/integrator_aliases.h"

namespace prism {

void add_integrator_aliases(const RenderOptions& options, const Scene& scene,
                            const std::string& integrator, ParamSet& params) {
  const std::string prefix = integrator + ".";
  if (options.light_samples) {
    const std::string n = std::to_string(*options.light_samples);
    params.set_alias(prefix + "light_samples", n, "-l " + n);
  }
  if (options.max_depth) {
    const std::string n = std::to_string(*options.max_depth);
    params.set_alias(prefix + "max_depth", n, "-m " + n);
  } else if (scene.settings.max_depth && !params.has(prefix + "max_depth")) {
    const std::string n = std::to_string(*scene.settings.max_depth);
    params.set_alias(prefix + "max_depth", n, "the scene file's max_depth " + n);
  }
  if (options.hemisphere_sampling) params.set_alias(prefix + "hemisphere", "true", "-H");
  if (options.two_sided_emitters) {
    params.set_alias(prefix + "two_sided_emitters", "true", "--two-sided-emitters");
  }
}

void record_integrator_aliases(const ParamSet& params, RenderSettings& settings) {
  const std::string prefix = settings.integrator + ".";
  settings.light_samples =
      int(params.get_int(prefix + "light_samples", settings.light_samples, 1, kMaxLightSamples));
  settings.max_depth = int(params.get_int(prefix + "max_depth", settings.max_depth, 0, kMaxDepth));
}

}  // namespace prism
