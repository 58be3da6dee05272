#pragma once
// Subcommands of the gproj command line. Each Register* adds its subcommand to the app and
// arranges for its handler to run when it is selected; handlers return the process exit code.

#include <CLI/CLI.hpp>

namespace gproj {

// Exit codes shared by all subcommands.
constexpr int kExitOk = 0;
constexpr int kExitInputError = 1;     // bad file, mesh or option value: nothing written
constexpr int kExitNotConverged = 3;   // finished without meeting the tolerance: result written
constexpr int kExitSolverFailure = 4;  // numerical failure: nothing written

// Registers `gproj planarize`; *exit_code receives the handler's exit code.
void RegisterPlanarizeCommand(CLI::App* app, int* exit_code);
// Registers `gproj grid` (noisy test grids).
void RegisterGridCommand(CLI::App* app, int* exit_code);
// Registers `gproj anet` and `gproj hnet`.
void RegisterNetCommands(CLI::App* app, int* exit_code);
// Registers `gproj marionette`.
void RegisterMarionetteCommand(CLI::App* app, int* exit_code);
// Registers `gproj combescure`, `gproj invert` and `gproj canal`.
void RegisterSuperCanalCommands(CLI::App* app, int* exit_code);
// Registers `gproj weingarten`.
void RegisterWeingartenCommand(CLI::App* app, int* exit_code);

}  // namespace gproj
