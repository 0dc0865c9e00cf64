#pragma once

#include <string>

#include "core/app/render_options.h"
#include "core/param_set.h"
#include "core/scene.h"

namespace prism {

/// The render flags that stand for integrator parameters. For the integrator in use, I, adds
/// to `params` as aliases (ParamSet::set_alias):
///   -l N  as I.light_samples=N
///   -m N  as I.max_depth=N; without -m, the scene file's settings.max_depth, unless --set
///         gives I.max_depth (flags override the scene file)
///   -H    as I.hemisphere=true
///   --two-sided-emitters  as I.two_sided_emitters=true
/// An integrator without such a parameter never reads the key: the flag is ignored. One that
/// has it reads the flag's value, and throws Error(kUsage) naming both when --set gives the
/// same key another value.
void add_integrator_aliases(const RenderOptions& options, const Scene& scene,
                            const std::string& integrator, ParamSet& params);

/// Sets settings.light_samples and settings.max_depth to I.light_samples and I.max_depth in
/// `params` (I = settings.integrator) where it has them, so that the output files record the
/// values in effect; elsewhere they keep the flag, scene-file or default values. Call once the
/// integrator has been built from `params` and check_component_params() has accepted them:
/// it reads the keys.
void record_integrator_aliases(const ParamSet& params, RenderSettings& settings);

}  // namespace prism
