#include "gproj/service/server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "gproj/service/hops.h"
#include "gproj/service/web_app.h"

namespace gproj::service {
namespace {

using Clock = std::chrono::steady_clock;

void SendJson(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(DumpJson(body), "application/json");
}

void SendError(httplib::Response& res, int status, const std::string& message) {
  SendJson(res, status, {{"error", message}});
}

// The request body as JSON; false (400 sent) when it is not JSON.
bool ParseBody(const std::string& text, httplib::Response& res, nlohmann::json* body) {
  try {
    *body = ParseRequestJson(text);
    return true;
  } catch (const RequestError& e) {
    SendError(res, 400, e.what());
  }
  return false;
}

bool ConstantTimeEquals(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i)
    diff |= static_cast<unsigned char>(a[i] ^ b[i % std::max<std::size_t>(1, b.size())]);
  return diff == 0;
}

std::string BearerToken(const httplib::Request& req) {
  const std::string auth = req.get_header_value("Authorization");
  const std::string prefix = "Bearer ";
  if (auth.compare(0, prefix.size(), prefix) == 0) return auth.substr(prefix.size());
  if (req.has_header("RhinoComputeKey")) return req.get_header_value("RhinoComputeKey");
  if (req.has_param("token")) return req.get_param_value("token");
  return "";
}

// Answers a submission: 201 {"id", "status", "url", ...extra}, or 400 naming the field (an option
// as options.NAME), or 429 when the table is full.
void SubmitRun(httplib::Response& res, const nlohmann::json& extra,
               const std::function<std::string()>& submit) {
  try {
    const std::string id = submit();
    nlohmann::json answer = {{"id", id}, {"status", "queued"}, {"url", "/api/runs/" + id}};
    for (auto it = extra.begin(); it != extra.end(); ++it) answer[it.key()] = it.value();
    SendJson(res, 201, answer);
  } catch (const OptionError& e) {
    SendError(res, 400, "options." + SpellOptions(e.what(), false));
  } catch (const InputError& e) {
    SendError(res, 400, SpellOptions(e.what(), false));
  } catch (const RunTableFull& e) {
    SendError(res, 429, e.what());
  }
}

}  // namespace

bool IsLoopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.compare(0, 4, "127.") == 0;
}

struct Service::Impl {
  explicit Impl(ServiceOptions o) : options(std::move(o)), table(options.runs) {
    if (options.web_dir.empty()) options.web_dir = DefaultWebDir();
    if (options.examples_dir.empty()) options.examples_dir = DefaultExamplesDir();
    web_files = LoadWebFiles(options.web_dir, &web_missing);
    examples = LoadExamples(options.examples_dir, options.request);
  }

  void Routes();
  // A POST route whose body is read here (whatever its Content-Type: no form decoding), limited
  // to max_body_bytes and parsed as JSON before `handler` sees it.
  void PostJson(
      const std::string& pattern,
      std::function<void(const httplib::Request&, httplib::Response&, const nlohmann::json&)>
          handler);
  void HopsSolve(const ProblemSpec& spec, const nlohmann::json& body, httplib::Response& res);

  ServiceOptions options;
  RunTable table;
  std::map<std::string, WebFile> web_files;
  std::string web_missing;  // a file of the web app that could not be read
  std::vector<Example> examples;
  // Event streams open: each holds one of the connection threads for as long as it runs, so at
  // most half of them may stream and the other half always serves requests.
  std::atomic<int> streams{0};
  httplib::Server server;
  int port = -1;
};

Service::Service(ServiceOptions options) {
  if (options.port < 0 || options.port > 65535)
    throw InputError("--port: " + std::to_string(options.port) + " is not a port (0 to 65535)");
  if (!IsLoopback(options.host) && options.token.empty())
    throw InputError("--host: serving on " + options.host +
                     " (not a loopback address) needs --token, which every request must then "
                     "carry");
  if (!options.token.empty() &&
      (options.token.size() < 8 || options.token.find_first_of(" \t\r\n") != std::string::npos))
    throw InputError("--token: must be at least 8 characters, none of them spaces");
  if (options.max_body_bytes < 1024) throw InputError("--max-body: must be at least 1024 bytes");
  if (options.connections < 4) throw InputError("--connections: must be at least 4");
  impl_ = std::make_unique<Impl>(std::move(options));
  impl_->Routes();
}

Service::~Service() { Stop(); }

int Service::Bind() {
  Impl& impl = *impl_;
  // cpp-httplib 0.11 listens with a backlog of 5, so a burst of clients (a Grasshopper
  // definition solving many components, a script's threads) overflows it and connections are
  // dropped; the listening socket is taken here and given the system's backlog after binding.
  int listening = -1;
  impl.server.set_socket_options([&listening](int sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    listening = sock;
  });
  if (impl.options.port == 0)
    impl.port = impl.server.bind_to_any_port(impl.options.host);
  else
    impl.port =
        impl.server.bind_to_port(impl.options.host, impl.options.port) ? impl.options.port : -1;
  if (impl.port <= 0)
    throw InputError("cannot listen on " + impl.options.host + ":" +
                     std::to_string(impl.options.port) +
                     " (the port is taken, or the address is not this machine's)");
  if (listening >= 0) ::listen(listening, SOMAXCONN);
  return impl.port;
}

const std::string& Service::WebAppMissing() const { return impl_->web_missing; }

void Service::Serve() { impl_->server.listen_after_bind(); }

void Service::Stop() {
  if (!impl_) return;
  // Runs first: a Hops solve or a stream waiting on a run returns, so the server's threads end.
  impl_->table.CancelAll();
  impl_->server.stop();
}

void Service::Impl::PostJson(
    const std::string& pattern,
    std::function<void(const httplib::Request&, httplib::Response&, const nlohmann::json&)>
        handler) {
  const std::size_t limit = options.max_body_bytes;
  server.Post(pattern, [limit, handler](const httplib::Request& req, httplib::Response& res,
                                        const httplib::ContentReader& reader) {
    const std::string length_header = req.get_header_value("Content-Length");
    if (!length_header.empty() && std::strtoull(length_header.c_str(), nullptr, 10) > limit)
      return SendError(res, 413,
                       "request: the body is larger than the service's limit of " +
                           std::to_string(limit) + " bytes (gproj serve --max-body)");
    std::string text;
    bool too_large = false;
    const bool read = reader([&](const char* data, std::size_t length) {
      if (text.size() + length > limit) {
        too_large = true;
        return false;
      }
      text.append(data, length);
      return true;
    });
    if (too_large)
      return SendError(res, 413,
                       "request: the body is larger than the service's limit of " +
                           std::to_string(limit) + " bytes (gproj serve --max-body)");
    if (!read) return SendError(res, 400, "request: the body could not be read");
    nlohmann::json body;
    if (ParseBody(text, res, &body)) handler(req, res, body);
  });
}

void Service::Impl::Routes() {
  const int threads = options.connections;
  server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server.set_payload_max_length(options.max_body_bytes);
  // A client that stops sending mid-request is dropped after 5 s (it holds a thread till then).
  server.set_read_timeout(5, 0);
  server.set_write_timeout(30, 0);
  server.set_keep_alive_max_count(100);

  const std::size_t max_body = options.max_body_bytes;
  server.set_error_handler(httplib::Server::HandlerWithResponse(
      [max_body](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        std::string message;
        if (res.status == 413)
          message = "request: the body is larger than the service's limit of " +
                    std::to_string(max_body) + " bytes (gproj serve --max-body)";
        else if (res.status == 404)
          message = req.method + " " + req.path + ": no such endpoint (GET /api lists them)";
        else
          message = "request: refused with HTTP status " + std::to_string(res.status);
        SendError(res, res.status, message);
        return httplib::Server::HandlerResponse::Handled;
      }));
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        std::string what = "unknown error";
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          what = e.what();
        } catch (...) {
        }
        SendError(res, 500, "internal error: " + what);
      });
  const std::string token = options.token;
  // The web app's own files (the page, its script and packages) hold nothing of the service's,
  // and a browser loads a page's modules without the token, so they are served without it; the
  // page then sends the token (from its ?token=) with every API request.
  server.set_pre_routing_handler(
      [this, token](const httplib::Request& req, httplib::Response& res) {
        if (token.empty() || ConstantTimeEquals(BearerToken(req), token) ||
            (req.method == "GET" && web_files.count(req.path)))
          return httplib::Server::HandlerResponse::Unhandled;
        SendError(res, 401,
                  "request: this service needs its token (Authorization: Bearer TOKEN, "
                  "RhinoComputeKey: TOKEN or ?token=TOKEN)");
        return httplib::Server::HandlerResponse::Handled;
      });

  const Registry& registry = Registry::Builtin();
  server.Get("/api", [](const httplib::Request&, httplib::Response& res) {
    SendJson(res, 200,
             {{"gproj", GprojVersion()},
              {"endpoints",
               {"GET /api/schema", "POST /api/runs", "GET /api/runs", "GET /api/runs/{id}",
                "GET /api/runs/{id}/events", "DELETE /api/runs/{id}", "POST /api/runs/{id}/resolve",
                "GET /hops", "GET /hops/{problem}", "POST /solve", "GET /", "GET /api/examples",
                "GET /api/examples/{name}", "POST /api/meshes"}}});
  });
  server.Get("/api/schema", [&registry](const httplib::Request&, httplib::Response& res) {
    SendJson(res, 200, registry.SchemaJson());
  });
  PostJson("/api/runs", [this, &registry](const httplib::Request& req, httplib::Response& res,
                                          const nlohmann::json& body) {
    SubmitRun(res, {},
              [&] { return table.Submit(ParseRunRequest(body, registry, options.request)); });
  });
  server.Get("/api/runs", [this](const httplib::Request&, httplib::Response& res) {
    SendJson(res, 200, {{"runs", table.List()}});
  });
  server.Get(R"(/api/runs/([0-9a-f]{16}))",
             [this](const httplib::Request& req, httplib::Response& res) {
               const auto run = table.Describe(req.matches[1], /*details=*/true);
               if (!run)
                 SendError(res, 404,
                           "run: no run " + std::string(req.matches[1]) +
                               " (finished runs are kept while they are among the "
                               "last " +
                               std::to_string(table.limits().max_kept) + ")");
               else
                 SendJson(res, 200, *run);
             });
  server.Delete(R"(/api/runs/([0-9a-f]{16}))", [this](const httplib::Request& req,
                                                      httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto run = table.Describe(id, false);
    if (!run) return SendError(res, 404, "run: no run " + id);
    if (!table.Cancel(id))
      return SendError(
          res, 409, "run: " + id + " has finished (" + run->at("status").get<std::string>() + ")");
    table.Wait(id, std::chrono::seconds(5));
    SendJson(res, 200, *table.Describe(id, false));
  });
  server.Get(R"(/api/runs/([0-9a-f]{16})/events)", [this](const httplib::Request& req,
                                                          httplib::Response& res) {
    const std::string id = req.matches[1];
    if (!table.Describe(id, false)) return SendError(res, 404, "run: no run " + id);
    std::size_t from = 0;
    const std::string last = req.has_header("Last-Event-ID") ? req.get_header_value("Last-Event-ID")
                                                             : req.get_param_value("from");
    if (!last.empty()) {
      char* end = nullptr;
      const unsigned long long n = std::strtoull(last.c_str(), &end, 10);
      if (end == last.c_str() || *end != '\0' || n > (1ull << 40))
        return SendError(res, 400, "from: expected an event number");
      from = static_cast<std::size_t>(n) + (req.has_header("Last-Event-ID") ? 1 : 0);
    }
    const int max_streams = options.connections / 2;
    if (++streams > max_streams) {
      --streams;
      return SendError(res, 429,
                       "events: " + std::to_string(max_streams) +
                           " event streams are open, the most this service serves (gproj serve "
                           "--connections); poll GET /api/runs/" +
                           id + " instead");
    }
    table.Follow(id, +1);
    auto next = std::make_shared<std::size_t>(from);
    auto idle = std::make_shared<Clock::time_point>(Clock::now());
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, id, next, idle](std::size_t, httplib::DataSink& sink) {
          std::vector<nlohmann::json> events;
          bool ended = false;
          if (!table.Events(id, *next, std::chrono::milliseconds(250), &events, &ended)) {
            sink.done();
            return true;
          }
          for (const nlohmann::json& event : events) {
            const std::string text = "id: " + std::to_string((*next)++) +
                                     "\nevent: " + event.at("event").get<std::string>() +
                                     "\ndata: " + DumpJson(event.at("data")) + "\n\n";
            if (!sink.write(text.data(), text.size())) return false;
          }
          if (ended && events.empty()) {
            sink.done();
            return true;
          }
          if (!events.empty()) {
            *idle = Clock::now();
          } else if (Clock::now() - *idle > std::chrono::seconds(1)) {
            // A comment: finds a client that went away while nothing happens.
            static const char kAlive[] = ": alive\n\n";
            if (!sink.write(kAlive, sizeof kAlive - 1)) return false;
            *idle = Clock::now();
          }
          return true;
        },
        [this, id](bool) {
          table.Follow(id, -1);
          --streams;
        });
  });
  PostJson(R"(/api/runs/([0-9a-f]{16})/resolve)",
           [this](const httplib::Request& req, httplib::Response& res, const nlohmann::json& body) {
             const std::string id = req.matches[1];
             const auto run = table.Describe(id, false);
             if (!run) return SendError(res, 404, "run: no run " + id);
             const auto finished = table.Finished(id);
             if (!finished)
               return SendError(res, 409,
                                "run: " + id + " has not finished (" +
                                    run->at("status").get<std::string>() + ")");
             SubmitRun(res, {{"from", id}},
                       [&] { return table.Submit(ResolveRequest(*finished, body), id); });
           });

  for (const auto& [path, file] : web_files) {
    const WebFile* served = &file;
    server.Get(path, [served](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(served->content, served->type);
    });
  }
  server.Get("/api/examples", [this](const httplib::Request&, httplib::Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (const Example& example : examples) list.push_back(ExampleJson(example, false));
    SendJson(res, 200, {{"examples", list}});
  });
  server.Get(R"(/api/examples/([a-z0-9_]+))", [this](const httplib::Request& req,
                                                     httplib::Response& res) {
    for (const Example& example : examples)
      if (example.name == req.matches[1]) return SendJson(res, 200, ExampleJson(example, true));
    std::string names;
    for (const Example& example : examples) names += (names.empty() ? "" : ", ") + example.name;
    SendError(res, 404, "example: no example " + std::string(req.matches[1]) + " (" + names + ")");
  });
  PostJson("/api/meshes",
           [this](const httplib::Request&, httplib::Response& res, const nlohmann::json& body) {
             try {
               SendJson(res, 200, ReadDroppedMesh(body, options.request));
             } catch (const InputError& e) {
               SendError(res, 400, e.what());
             }
           });

  server.Get("/hops", [&registry](const httplib::Request&, httplib::Response& res) {
    SendJson(res, 200, HopsComponents(registry));
  });
  server.Get(
      R"(/hops/([a-z_]+))", [&registry](const httplib::Request& req, httplib::Response& res) {
        const ProblemSpec* spec = registry.Find(req.matches[1]);
        if (!spec || !HasHopsComponent(*spec))
          return SendError(
              res, 404,
              "hops: no component " + std::string(req.matches[1]) + " (GET /hops lists them)");
        SendJson(res, 200, HopsDescription(*spec));
      });
  auto solve = [this, &registry](const nlohmann::json& body, httplib::Response& res,
                                 const ProblemSpec* named) {
    const ProblemSpec* spec = named ? named : HopsProblem(body, registry);
    if (!spec)
      return SendJson(res, 404,
                      {{"values", nlohmann::json::array()},
                       {"errors",
                        {"pointer: names no gproj component (expected hops/<problem>; "
                         "GET /hops lists them)"}},
                       {"warnings", nlohmann::json::array()}});
    HopsSolve(*spec, body, res);
  };
  PostJson("/solve", [solve](const httplib::Request&, httplib::Response& res,
                             const nlohmann::json& body) { solve(body, res, nullptr); });
  PostJson(R"(/hops/([a-z_]+))",
           [solve, &registry](const httplib::Request& req, httplib::Response& res,
                              const nlohmann::json& body) {
             const ProblemSpec* spec = registry.Find(req.matches[1]);
             if (!spec || !HasHopsComponent(*spec))
               return SendError(res, 404, "hops: no component " + std::string(req.matches[1]));
             solve(body, res, spec);
           });
}

void Service::Impl::HopsSolve(const ProblemSpec& spec, const nlohmann::json& body,
                              httplib::Response& res) {
  std::vector<std::string> errors, warnings;
  std::string id;
  try {
    id = table.Submit(
        ParseRunRequest(HopsRunRequest(body, spec), Registry::Builtin(), options.request));
  } catch (const OptionError& e) {
    errors.push_back(SpellOptions(e.what(), false));
  } catch (const InputError& e) {
    errors.push_back(SpellOptions(e.what(), false));
  } catch (const RunTableFull& e) {
    return SendJson(res, 429, HopsAnswer(spec, nullptr, nullptr, "failed", {e.what()}, {}));
  }
  if (id.empty())
    return SendJson(res, 200, HopsAnswer(spec, nullptr, nullptr, "failed", errors, {}));
  while (!table.Wait(id, std::chrono::seconds(1)))
    if (!table.Describe(id, false)) break;
  const auto run = table.Describe(id, true);
  const auto finished = table.Finished(id);
  const std::string status = run ? run->at("status").get<std::string>() : "failed";
  if (run && run->contains("error")) errors.push_back(run->at("error").get<std::string>());
  const RunResult* result = finished ? &finished->result : nullptr;
  if (result)
    for (const RunMessage& message : result->messages)
      if (message.kind == RunMessage::Kind::kWarning)
        warnings.push_back(SpellOptions(message.text, false));
  if (status == "not-converged" && result)
    warnings.push_back("not converged: " + result->report.termination);
  SendJson(res, 200,
           HopsAnswer(spec, result, run ? run->value("report", nlohmann::json()) : nullptr, status,
                      errors, warnings));
}

}  // namespace gproj::service
