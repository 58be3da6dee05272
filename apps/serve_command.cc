// `gproj serve`: the HTTP service (gproj/service/server.h, docs/service.md) until Ctrl-C or
// SIGTERM. It prints the address it listens on; with --port 0 the port is chosen and printed.
#include <signal.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <thread>

#include "apps/commands.h"
#include "gproj/service/server.h"
#include "gproj/service/web_app.h"

namespace gproj {
namespace {

volatile std::sig_atomic_t stop_signal = 0;

extern "C" void OnStopSignal(int signal_number) { stop_signal = signal_number; }

int RunServe(service::ServiceOptions options) {
  if (options.token.empty())
    if (const char* token = std::getenv("GPROJ_SERVE_TOKEN")) options.token = token;
  std::unique_ptr<service::Service> server;
  int port = 0;
  try {
    server = std::make_unique<service::Service>(options);
    port = server->Bind();
  } catch (const InputError& e) {
    std::cerr << "gproj serve: " << e.what() << "\n";
    return kExitInputError;
  }
  // Ctrl-C and SIGTERM set a flag, whichever thread takes them (the BLAS library starts threads
  // of its own); a watcher stops the server when it is set. A closed client socket is an error
  // of the write, not a signal.
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  signal(SIGPIPE, SIG_IGN);
  const std::string host =
      options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
  std::printf(
      "gproj serve: listening on http://%s:%d/ (the web app at /, the API at /api, Hops "
      "components at /hops%s); Ctrl-C stops\n",
      host.c_str(), port, options.token.empty() ? "" : ", token required");
  std::fflush(stdout);
  if (!server->WebAppMissing().empty())
    std::fprintf(stderr,
                 "gproj serve: the web app is not installed (%s is missing; npm ci --prefix web "
                 "installs it); the API and the Hops components are served\n",
                 server->WebAppMissing().c_str());
  std::atomic<bool> served{false};
  std::thread watcher([&server, &served] {
    while (!stop_signal && !served) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    server->Stop();
  });
  server->Serve();
  served = true;
  watcher.join();
  server.reset();  // cancels the runs still going and joins their workers
  std::printf("gproj serve: stopped\n");
  return kExitOk;
}

}  // namespace

void RegisterServeCommand(CLI::App* app, int* exit_code) {
  auto options = std::make_shared<service::ServiceOptions>();
  CLI::App* cmd = app->add_subcommand(
      "serve",
      "Serve gproj over HTTP (docs/service.md): the registry, runs with live iteration streams, "
      "cancellation and warm re-solves, and Grasshopper Hops components. Binds 127.0.0.1 by "
      "default; any other --host needs --token.");
  cmd->add_option("--port", options->port, "Port to listen on (0: any free port, printed)")
      ->default_val(8765);
  cmd->add_option("--host", options->host,
                  "Address to bind; anything but a loopback address needs --token")
      ->default_val("127.0.0.1");
  cmd->add_option("--token", options->token,
                  "Secret every request must carry (Authorization: Bearer TOKEN, "
                  "RhinoComputeKey: TOKEN or ?token=TOKEN); also read from GPROJ_SERVE_TOKEN")
      ->type_name("TOKEN");
  cmd->add_option("--max-body", options->max_body_bytes, "Largest request body [bytes]")
      ->default_val(options->max_body_bytes);
  cmd->add_option("--connections", options->connections,
                  "Requests served at once; at most half of them may be event streams")
      ->default_val(options->connections)
      ->check(CLI::Range(4, 1024));
  cmd->add_option("--max-runs", options->runs.max_running,
                  "Runs executing at once (0: one per core)")
      ->default_val(0);
  cmd->add_option("--max-queued", options->runs.max_queued,
                  "Runs waiting beyond those; more are refused with 429")
      ->default_val(options->runs.max_queued);
  cmd->add_option("--max-seconds", options->runs.max_seconds,
                  "A run still going after this is stopped (not-converged) [s]")
      ->default_val(options->runs.max_seconds)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-vertices", options->request.max_vertices,
                  "Most vertices (and faces) of an input mesh")
      ->default_val(options->request.max_vertices)
      ->check(CLI::PositiveNumber);
  cmd->add_option("--web", options->web_dir, "The web app's folder (app/ and node_modules/)")
      ->default_str(service::DefaultWebDir())
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--examples", options->examples_dir, "The shipped examples' folder")
      ->default_str(service::DefaultExamplesDir())
      ->check(CLI::ExistingDirectory);
  cmd->callback([options, exit_code]() {
    options->request.max_faces = options->request.max_vertices;
    *exit_code = RunServe(*options);
  });
}

}  // namespace gproj
