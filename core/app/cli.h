#pragma once

namespace prism {

/// Parses the command line and runs the chosen command (render, info, list, colorspaces,
/// convert, and the benchmarking commands when registered).
/// Arguments that start with neither a command nor a top-level flag run `render`, so that
/// `prism -t 8 -s 64 -r 480 360 -f out.png scene.dae` works unchanged. Returns the
/// process exit code: 0 on success (and for --help/--version), 2 for command-line syntax errors,
/// which are printed as one line on stderr. Other failures throw prism::Error for main().
int run_cli(int argc, const char* const* argv);

}  // namespace prism
