#pragma once
// Subcommands of the gproj command line. Each Register* adds its subcommand to the app and
// arranges for its handler to run when it is selected; handlers return the process exit code.

#include <CLI/CLI.hpp>

#include "apps/command_support.h"
#include "gproj/problems/run/registry.h"

namespace gproj {

// Registers the subcommand of a problem of the registry (gproj/problems/run/registry.h), generated
// from its spec; *exit_code receives the handler's exit code. `spec` must outlive `app`.
void RegisterProblemCommand(CLI::App* app, const ProblemSpec& spec, int* exit_code);
// Registers `gproj schema` (the registry as JSON).
void RegisterSchemaCommand(CLI::App* app, int* exit_code);
// Registers `gproj serve` (the HTTP service, gproj/service/server.h).
void RegisterServeCommand(CLI::App* app, int* exit_code);

}  // namespace gproj
