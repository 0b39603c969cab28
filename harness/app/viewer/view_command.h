#pragma once
// `oitbench view`: the interactive viewer (GLFW window + Dear ImGui) on top
// of the technique registry and the harness's frame path.
#include "harness/app/commands.h"
#include "harness/app/viewer/view_options.h"

namespace CLI {
class App;
}

namespace oit {

// Registers the subcommand and its options on `app`; returns it.
CLI::App* add_view_command(CLI::App& app, ViewOptions& options);

// Throws std::runtime_error with advice (render/bench or xvfb-run) when no
// display can be opened.
int run_view(const CommonOptions& common, const ViewOptions& options);

}  // namespace oit
