// The gproj command line: one subcommand per problem of the registry, generated from its spec,
// `gproj schema` and `gproj serve`.
#include <glog/logging.h>

#include <cstring>
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
  app.set_version_flag("--version", std::string("gproj ") + gproj::GprojVersion());
  int exit_code = gproj::kExitOk;
  for (const gproj::ProblemSpec& spec : gproj::Registry::Builtin().problems())
    gproj::RegisterProblemCommand(&app, spec, &exit_code);
  gproj::RegisterSchemaCommand(&app, &exit_code);
  gproj::RegisterServeCommand(&app, &exit_code);
  gproj::RefuseEmptyValues(&app);
  // An unknown subcommand is refused before any --help after it could print the main help.
  std::string commands;
  bool known = false;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    commands += (commands.empty() ? "" : ", ") + command->get_name();
    known = known || (argc > 1 && command->get_name() == argv[1]);
  }
  if (argc > 1 && argv[1][0] != '-' && !known) {
    std::cerr << "gproj: unknown command '" << argv[1] << "' (commands: " << commands << ")\n";
    return gproj::kExitInputError;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, naming the option and the rule broken; --help explains every option.
    std::cerr << "gproj: " << e.what() << " (see gproj --help)\n";
    return gproj::kExitInputError;
  }
  return exit_code;
}
