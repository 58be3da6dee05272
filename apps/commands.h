#pragma once
// Subcommands of the gproj command line. Each Register* adds its subcommand to the app and
// arranges for its handler to run when it is selected; handlers return the process exit code.

#include <CLI/CLI.hpp>

#include "apps/command_support.h"

namespace gproj {

// Registers `gproj planarize`; *exit_code receives the handler's exit code.
void RegisterPlanarizeCommand(CLI::App* app, int* exit_code);
// Registers `gproj grid` (noisy test grids).
void RegisterGridCommand(CLI::App* app, int* exit_code);
// Registers `gproj anet` and `gproj hnet`.
void RegisterNetCommands(CLI::App* app, int* exit_code);
// Registers `gproj marionette`.
void RegisterMarionetteCommand(CLI::App* app, int* exit_code);
// Registers `gproj combescure`, `gproj invert`, `gproj canal`, `gproj beams` and
// `gproj mrevolution`.
void RegisterSuperCanalCommands(CLI::App* app, int* exit_code);
// Registers `gproj weingarten`.
void RegisterWeingartenCommand(CLI::App* app, int* exit_code);
// Registers `gproj field` (curvature direction fields of triangle meshes).
void RegisterFieldCommand(CLI::App* app, int* exit_code);
// Registers `gproj remesh` (field-aligned quad remeshing of triangle meshes).
void RegisterRemeshCommand(CLI::App* app, int* exit_code);

}  // namespace gproj
