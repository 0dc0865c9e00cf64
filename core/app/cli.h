#pragma once

#include <string>
#include <vector>

#include "core/app/render_options.h"

namespace prism {

/// Parses the command line and runs the chosen command (render, info, list, colorspaces,
/// convert, and the benchmarking commands when registered).
/// Arguments that start with neither a command nor a top-level flag run `render`, so that
/// `prism -t 8 -s 64 -r 480 360 -f out.png scene.dae` works unchanged. Returns the
/// process exit code: 0 on success (and for --help/--version), 2 for command-line syntax errors,
/// which are printed as one line on stderr. Other failures throw prism::Error for main().
int run_cli(int argc, const char* const* argv);

/// Parses the arguments of `prism render` (those after the word "render") into RenderOptions with
/// the grammar run_cli() uses, without checking the values (validate_render_options() does) or
/// running anything. Throws Error(kUsage) with CLI11's message, in one line, on a syntax error
/// (and for --help). For the fuzz target of the render options (tests/fuzz/).
RenderOptions parse_render_arguments(const std::vector<std::string>& arguments);

}  // namespace prism
