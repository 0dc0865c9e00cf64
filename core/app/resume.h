#pragma once

#include <optional>

#include "core/app/render_options.h"
#include "core/app/render_state.h"

namespace prism {

/// The options of a render resumed from `state` (--resume): the options stored in the
/// checkpoint, with only what does not change the image taken from `given` (the resume command
/// line): --threads, --quiet and --time-limit (all three per run), --checkpoint-interval (else
/// the stored one) and --checkpoint (else the stored checkpoint path, else the resumed file). Any other
/// option `given` sets to a value other than the stored one is Error(kUsage) naming it and both
/// values.
RenderOptions resumed_options(const RenderOptions& given, const RenderStateRecord& state,
                              const std::filesystem::path& resumed_file);

/// `options` with the paths it names (scene, output, environment map, OCIO config, checkpoint)
/// made absolute, so that a checkpoint resumes from any folder.
RenderOptions with_absolute_paths(const RenderOptions& options);

/// Throws Error(kUsage, exit 2) naming the checkpoint and the first differing field unless
/// `identity` (of the render about to continue) equals the checkpoint's: the scene file (or a
/// file it names) changed, or the options or OCIO config differ.
void check_resume_identity(const nlohmann::json& identity, const RenderStateRecord& state,
                           const std::filesystem::path& resumed_file);

}  // namespace prism
