// The gproj command line.
#include <glog/logging.h>

#include <iostream>

#include "apps/commands.h"

int main(int argc, char** argv) {
  // Ceres reports line-search trouble through glog; the commands report their runs themselves.
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_ERROR;
  CLI::App app{
      "gproj: guided projection for architectural geometry.\n"
      "Makes freeform meshes buildable by solving systems of quadratic constraints\n"
      "(planar and circular quads, ...) with Gauss-Newton-style guided projection and sparse "
      "Cholesky."};
  app.require_subcommand(1);
  int exit_code = gproj::kExitOk;
  gproj::RegisterPlanarizeCommand(&app, &exit_code);
  gproj::RegisterGridCommand(&app, &exit_code);
  gproj::RegisterNetCommands(&app, &exit_code);
  gproj::RegisterMarionetteCommand(&app, &exit_code);
  gproj::RegisterSuperCanalCommands(&app, &exit_code);
  gproj::RegisterWeingartenCommand(&app, &exit_code);
  gproj::RegisterFieldCommand(&app, &exit_code);
  gproj::RegisterRemeshCommand(&app, &exit_code);
  gproj::RefuseEmptyValues(&app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, naming the option and the rule broken; --help explains every option.
    std::cerr << "gproj: " << e.what() << " (see gproj --help)\n";
    return gproj::kExitInputError;
  }
  return exit_code;
}
