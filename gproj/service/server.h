#pragma once
// `gproj serve`: the HTTP service over the registry (cpp-httplib). Endpoints (docs/service.md):
//   GET    /api/schema                the registry (problems, inputs, options, outputs)
//   POST   /api/runs                  a run request -> {"id", "status"} (201)
//   GET    /api/runs                  the runs kept: id, problem, status
//   GET    /api/runs/{id}             status, and report and result once finished
//   GET    /api/runs/{id}/events      the run's columns, records, messages and end (SSE)
//   DELETE /api/runs/{id}             cancels the run
//   POST   /api/runs/{id}/resolve     a warm re-solve of a finished run after edits
//   GET    /hops, GET /hops/{name}    Hops component descriptions
//   POST   /solve, POST /hops/{name}  a Hops solve
//   GET    /                          the web app (web/app, three.js and lil-gui from npm)
//   GET    /api/examples[/{name}]     the shipped examples the app opens
//   POST   /api/meshes                a mesh's file contents read -> {"vertices", "faces"}
// It binds to 127.0.0.1 by default and refuses any other address without a token, which every
// request must then carry. Bodies are limited in size, runs in number, time and mesh size; every
// bad request gets a JSON {"error": "..."} naming the field and the rule broken.

#include <functional>
#include <memory>
#include <string>

#include "gproj/service/run_request.h"
#include "gproj/service/run_table.h"

namespace gproj::service {

struct ServiceOptions {
  std::string host = "127.0.0.1";
  int port = 8765;  // 0: any free port
  // Required for any host but a loopback one; then every request must carry it, as
  // "Authorization: Bearer TOKEN", "RhinoComputeKey: TOKEN" (Hops' API key) or "?token=TOKEN".
  std::string token;
  std::size_t max_body_bytes = 64u << 20;
  int connections = 32;  // requests served at once (streams included)
  RunLimits runs;
  RequestLimits request;
  std::string web_dir;       // web/ (app/ and node_modules/); empty: DefaultWebDir()
  std::string examples_dir;  // examples/data; empty: DefaultExamplesDir()
};

// Whether `host` is a loopback address (127.0.0.0/8, ::1, localhost).
bool IsLoopback(const std::string& host);

class Service {
 public:
  // Throws InputError for options that may not be served (another host without a token, a bad
  // port or limit).
  explicit Service(ServiceOptions options);
  ~Service();
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  // Binds the address; returns the port (the one chosen when the options ask for 0). Throws
  // InputError when it cannot bind.
  int Bind();
  // Serves until Stop (from another thread or a signal's watcher).
  void Serve();
  // The web app's file that could not be read at start (empty: the app is served).
  const std::string& WebAppMissing() const;
  // Cancels every run and stops serving; Serve returns once the requests in flight have ended.
  void Stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gproj::service
