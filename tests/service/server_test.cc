// `gproj serve` as a real process: the API (schema, runs, status, the event stream, cancel,
// warm re-solve), Hops, and what it refuses (bad JSON, bad fields, large bodies, no token,
// too many runs), and that it stays up through all of it.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <atomic>
#include <thread>

#include "gproj/problems/run/registry.h"
#include "service/service_test_util.h"

namespace gproj::service {
namespace {

nlohmann::json GridMesh() { return MeshToJson(ReadMesh(ExamplePath("noisy_grid_21x21.obj"))); }

nlohmann::json PlanarizeRequest(const nlohmann::json& mesh, nlohmann::json options = {}) {
  return {{"problem", "planarize"},
          {"inputs", {{"mesh", mesh}, {"fixed", {0}}}},
          {"options", options.is_null() ? nlohmann::json::object() : options}};
}

// A noisy n x n grid of spacing 1 over the saddle z = 0.02 (i² − j²), noise 10% of the spacing.
nlohmann::json SaddleMesh(int n) {
  nlohmann::json mesh = {{"vertices", nlohmann::json::array()}, {"faces", nlohmann::json::array()}};
  unsigned state = 12345;
  auto noise = [&state] {
    state = state * 1103515245u + 12345u;
    return ((state >> 8) % 1000) / 1000.0 - 0.5;
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      mesh["vertices"].push_back(
          {i + 0.1 * noise(), j + 0.1 * noise(), 0.02 * (i * i - j * j) + 0.1 * noise()});
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j)
      mesh["faces"].push_back({i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1});
  return mesh;
}

// A noisy n x n grid planarised by plain steps to a tolerance it cannot meet: it runs until
// it is stopped.
nlohmann::json SlowRequest(int n) {
  return PlanarizeRequest(SaddleMesh(n),
                          {{"tolerance", 1e-300}, {"max_iterations", 100000}, {"monotone", false}});
}

std::string Post(httplib::Client& client, const std::string& path, const nlohmann::json& body,
                 int* status) {
  const auto res = client.Post(path.c_str(), body.dump(), "application/json");
  *status = res ? res->status : -1;
  return res ? res->body : "no answer: " + httplib::to_string(res.error());
}

std::string Submit(httplib::Client& client, const nlohmann::json& body) {
  int status = 0;
  const std::string answer = Post(client, "/api/runs", body, &status);
  EXPECT_EQ(status, 201) << answer;
  return status == 201 ? nlohmann::json::parse(answer).at("id").get<std::string>() : "";
}

// Opens GET /api/runs/ID/events on a raw socket and waits for the stream's first bytes; the
// socket (the caller closes it), or -1.
int OpenStream(int port, const std::string& id) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address = {};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return -1;
  const std::string get = "GET /api/runs/" + id + "/events HTTP/1.1\r\nHost: x\r\n\r\n";
  char buffer[4096];
  if (send(fd, get.data(), get.size(), 0) != static_cast<ssize_t>(get.size()) ||
      recv(fd, buffer, sizeof buffer, 0) <= 0) {
    close(fd);
    return -1;
  }
  return fd;
}

TEST(ServerTest, RunsAreServedStreamedCancelledAndResolved) {
  ServerProcess server({});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();

  // The schema is the registry's.
  auto schema = client.Get("/api/schema");
  ASSERT_TRUE(schema);
  EXPECT_EQ(schema->status, 200);
  EXPECT_EQ(nlohmann::json::parse(schema->body), Registry::Builtin().SchemaJson());

  // A run: converged, planar, the fixed vertex where it was, faces in the input's order.
  const nlohmann::json mesh = GridMesh();
  const std::string id = Submit(client, PlanarizeRequest(mesh));
  const nlohmann::json run = AwaitRun(client, id);
  ASSERT_EQ(run.at("status"), "converged") << run.dump().substr(0, 2000);
  const nlohmann::json& out = run.at("result").at("output");
  EXPECT_EQ(out.at("faces"), mesh.at("faces"));
  EXPECT_LT(MaxDiagonalGap(out), 1e-7);
  EXPECT_EQ(out.at("vertices")[0], mesh.at("vertices")[0]);
  EXPECT_EQ(run.at("report").at("status"), "CONVERGENCE");
  // The measure the tolerance bounds, and the bound, met.
  EXPECT_EQ(run.at("report").at("tolerance_measure"), "max_planarity");
  EXPECT_LE(run.at("report").at("final").at("max_planarity").get<double>(),
            run.at("report").at("tolerance").get<double>());
  const int iterations = run.at("report").at("iterations");

  // Its events, streamed after the fact: the columns, one record per iterate, the end.
  auto events = client.Get(("/api/runs/" + id + "/events").c_str());
  ASSERT_TRUE(events);
  EXPECT_EQ(events->get_header_value("Content-Type"), "text/event-stream");
  int records = 0, ends = 0;
  std::istringstream lines(events->body);
  for (std::string line; std::getline(lines, line);) {
    records += line == "event: record";
    ends += line == "event: end";
  }
  EXPECT_EQ(records, iterations + 1);  // the initial iterate too
  EXPECT_EQ(ends, 1);
  // Iterate events show the run live: the first iteration's always, only the latest kept.
  std::vector<nlohmann::json> iterates;
  std::istringstream event_lines(events->body);
  for (std::string line, event; std::getline(event_lines, line);) {
    if (line.rfind("event: ", 0) == 0) event = line.substr(7);
    if (line.rfind("data: ", 0) == 0 && event == "iterate")
      iterates.push_back(nlohmann::json::parse(line.substr(6)));
  }
  ASSERT_GE(iterates.size(), 1u);
  for (std::size_t i = 0; i + 1 < iterates.size(); ++i)
    EXPECT_EQ(iterates[i], nlohmann::json({{"superseded", true}}));
  EXPECT_GE(iterates.back().at("iteration").get<int>(), 1);
  EXPECT_LE(iterates.back().at("iteration").get<int>(), iterations);
  ASSERT_EQ(iterates.back().at("vertices").size(), mesh.at("vertices").size());
  EXPECT_EQ(iterates.back().at("vertices")[0], mesh.at("vertices")[0]);  // held: the corner
  EXPECT_NE(events->body.find("\"status\":\"converged\""), std::string::npos);
  EXPECT_NE(events->body.find("\"tolerance_measure\":\"max_planarity\""), std::string::npos);

  // A warm re-solve after moving one vertex by 5% of an edge: it stays where it was put.
  const nlohmann::json& before = out.at("vertices")[220];
  const nlohmann::json to = {before[0].get<double>() + 0.05, before[1], before[2]};
  int status = 0;
  const std::string answer = Post(client, "/api/runs/" + id + "/resolve",
                                  {{"moved", {{{"vertex", 220}, {"to", to}}}}}, &status);
  ASSERT_EQ(status, 201) << answer;
  const nlohmann::json resolved = AwaitRun(client, nlohmann::json::parse(answer).at("id"));
  ASSERT_EQ(resolved.at("status"), "converged") << resolved.dump().substr(0, 2000);
  EXPECT_EQ(resolved["result"]["output"]["vertices"][220], to);
  EXPECT_EQ(resolved["result"]["output"]["vertices"][0], mesh["vertices"][0]);
  EXPECT_LT(MaxDiagonalGap(resolved["result"]["output"]), 1e-7);
  EXPECT_LE(resolved["report"]["iterations"].get<int>(), iterations);
  // Bad edits are refused, naming the field.
  const std::string refused = Post(client, "/api/runs/" + id + "/resolve",
                                   {{"moved", {{{"vertex", 441}, {"to", to}}}}}, &status);
  EXPECT_EQ(status, 400);
  EXPECT_NE(refused.find("moved[0].vertex: vertex 441 is out of range"), std::string::npos)
      << refused;
  const std::string twice =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", {{{"vertex", 3}, {"to", to}}, {{"vertex", 3}, {"to", to}}}}}, &status);
  EXPECT_EQ(status, 400);
  EXPECT_NE(twice.find("moved[1].vertex: vertex 3 is moved twice"), std::string::npos) << twice;

  // A rule the run checks itself (two options that exclude each other): queued, then failed
  // with the message in "error".
  const std::string joined =
      Submit(client, PlanarizeRequest(mesh, {{"fix_boundary", true}, {"glide_boundary", true}}));
  const nlohmann::json failed = AwaitRun(client, joined);
  EXPECT_EQ(failed.at("status"), "failed");
  EXPECT_NE(failed.value("error", "").find("cannot be both fixed and gliding"), std::string::npos)
      << failed.dump();

  // A new edit supersedes a stale one: the first of two re-solves from one run is cancelled.
  const nlohmann::json slow_options = {{"tolerance", 1e-300}, {"max_iterations", 100000}};
  const nlohmann::json& at_221 = out.at("vertices")[221];
  const nlohmann::json to_221 = {at_221[0].get<double>() + 0.05, at_221[1], at_221[2]};
  const std::string stale_answer =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", {{{"vertex", 220}, {"to", to}}}}, {"options", slow_options}}, &status);
  ASSERT_EQ(status, 201) << stale_answer;
  const std::string newer_answer =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", {{{"vertex", 221}, {"to", to_221}}}}, {"options", slow_options}}, &status);
  ASSERT_EQ(status, 201) << newer_answer;
  EXPECT_EQ(AwaitRun(client, nlohmann::json::parse(stale_answer).at("id")).at("status"),
            "cancelled");
  const std::string newer = nlohmann::json::parse(newer_answer).at("id");
  const auto described = client.Get(("/api/runs/" + newer).c_str());
  ASSERT_TRUE(described);
  EXPECT_EQ(nlohmann::json::parse(described->body).at("from"), id);
  client.Delete(("/api/runs/" + newer).c_str());

  // A long run, cancelled while it runs.
  const std::string slow = Submit(client, SlowRequest(61));
  ASSERT_EQ(AwaitStatus(client, slow, {"queued"}).at("status"), "running");
  const auto cancelled = client.Delete(("/api/runs/" + slow).c_str());
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(cancelled->status, 200) << cancelled->body;
  EXPECT_EQ(AwaitRun(client, slow).at("status"), "cancelled");
  const auto again = client.Delete(("/api/runs/" + slow).c_str());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 409);

  // A client that follows a run's stream and goes away cancels it.
  const std::string followed = Submit(client, SlowRequest(61));
  const int stream = OpenStream(server.port(), followed);
  ASSERT_GE(stream, 0);  // the stream started
  close(stream);
  EXPECT_EQ(AwaitRun(client, followed).at("status"), "cancelled");

  EXPECT_TRUE(server.Alive());
  EXPECT_EQ(server.Stop(), 0);
}

// A drag in the web app: one vertex of a planar result moved by 5% of the spacing and re-solved
// to 1e-3 from that result. The re-solve starts soft-free (closeness and fairness off), so it
// restores planarity in one or two iterations around the moved vertex instead of re-running
// the soft terms' fade over the whole mesh.
TEST(ServerTest, DragReSolvesStartSoftFreeAndStayLocal) {
  ServerProcess server({});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  const int n = 41;
  const nlohmann::json mesh = SaddleMesh(n);
  const std::string id = Submit(client, PlanarizeRequest(mesh, {{"tolerance", 1e-6}}));
  const nlohmann::json run = AwaitRun(client, id);
  ASSERT_EQ(run.at("status"), "converged") << run.dump().substr(0, 2000);
  EXPECT_FALSE(run.at("report").contains("soft_free_start"));
  const nlohmann::json& start = run.at("result").at("output").at("vertices");

  const int v = (n / 2) * n + n / 3;
  const nlohmann::json to = {start[v][0], start[v][1], start[v][2].get<double>() + 0.05};
  int status = 0;
  const std::string answer =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", {{{"vertex", v}, {"to", to}}}}, {"options", {{"tolerance", 1e-3}}}}, &status);
  ASSERT_EQ(status, 201) << answer;
  const nlohmann::json resolved = AwaitRun(client, nlohmann::json::parse(answer).at("id"));
  ASSERT_EQ(resolved.at("status"), "converged") << resolved.dump().substr(0, 2000);
  const nlohmann::json& report = resolved.at("report");
  EXPECT_EQ(report.at("soft_free_start"), true);
  EXPECT_LE(report.at("iterations").get<int>(), 2);
  const nlohmann::json& out = resolved.at("result").at("output");
  EXPECT_EQ(out.at("vertices")[v], to);
  EXPECT_LT(MaxDiagonalGap(out), 1e-3);
  // Its neighbours follow it, none further than it was moved, and most of the mesh stays put
  // (a PQ mesh passes an edit on along its strips, so the rows and columns through the vertex
  // move too).
  auto moved = [&](int w) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c)
      d = std::max(d, std::abs(out["vertices"][w][c].get<double>() - start[w][c].get<double>()));
    return d;
  };
  EXPECT_GT(moved(v + 1), 1e-3);
  int followed = 0;
  for (int w = 0; w < n * n; ++w) {
    if (w != v) EXPECT_LE(moved(w), 0.05) << "vertex " << w;
    followed += moved(w) > 5e-3;
  }
  EXPECT_LT(followed, n * n / 10);

  // Asked for, the soft terms come back: closeness and fairness on from the start, as a run.
  const std::string soft =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", {{{"vertex", v}, {"to", to}}}}, {"soft_terms", true}}, &status);
  ASSERT_EQ(status, 201) << soft;
  const nlohmann::json with_soft = AwaitRun(client, nlohmann::json::parse(soft).at("id"));
  ASSERT_EQ(with_soft.at("status"), "converged") << with_soft.dump().substr(0, 2000);
  EXPECT_FALSE(with_soft.at("report").contains("soft_free_start"));
  EXPECT_EQ(with_soft["result"]["output"]["vertices"][v], to);
  const std::string bad =
      Post(client, "/api/runs/" + id + "/resolve",
           {{"moved", nlohmann::json::array()}, {"soft_terms", "yes"}}, &status);
  EXPECT_EQ(status, 400);
  EXPECT_NE(bad.find("soft_terms: expected true or false"), std::string::npos) << bad;
}

TEST(ServerTest, BadRequestsGetClearErrorsAndTheServiceStaysUp) {
  ServerProcess server({"--max-body", "200000"});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  auto expect = [&](const httplib::Result& res, int status, const std::string& part) {
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, status) << res->body;
    const nlohmann::json body = nlohmann::json::parse(res->body, nullptr, false);
    ASSERT_TRUE(body.is_object()) << res->body;
    EXPECT_NE(body.value("error", "").find(part), std::string::npos) << res->body;
  };
  expect(client.Post("/api/runs", "{\"problem\": \"planarize\",", "application/json"), 400,
         "request: the body is not JSON");
  expect(client.Post("/api/runs", "{\"problem\": \"planarise\"}", "application/json"), 400,
         "problem: no problem named \"planarise\"");
  nlohmann::json body = PlanarizeRequest(GridMesh());
  body["inputs"]["mesh"]["vertices"][5] = {0, 0};
  expect(client.Post("/api/runs", body.dump(), "application/json"), 400,
         "inputs.mesh.vertices[5]: expected a point [x, y, z]");
  body = PlanarizeRequest(GridMesh(), {{"min_angle", 75}});
  expect(client.Post("/api/runs", body.dump(), "application/json"), 400, "options.");
  expect(client.Post("/api/runs", body.dump(), "application/json"), 400, "min_angle");
  const std::string large(300000, ' ');
  expect(client.Post("/api/runs", large, "application/json"), 413,
         "larger than the service's limit of 200000 bytes");
  expect(client.Get("/api/runs/0123456789abcdef"), 404, "run: no run 0123456789abcdef");
  expect(client.Get("/etc/passwd"), 404, "no such endpoint");
  expect(client.Get("/api/runs/../../etc/passwd"), 404, "");
  // Deeply nested JSON is refused, not a crash.
  expect(client.Post("/api/runs", std::string(100000, '['), "application/json"), 400,
         "nests deeper than 64 levels");
  expect(client.Post("/api/runs",
                     "{\"problem\": \"planarize\", \"inputs\": {\"mesh\": " +
                         std::string(90000, '[') + std::string(90000, ']') + "}}",
                     "application/json"),
         400, "nests deeper than 64 levels");
  // Invalid UTF-8 in the path or the body: answered, not fatal.
  expect(client.Get("/nope%ff"), 404, "no such endpoint");
  expect(client.Post("/api/runs", "{\"problem\": \"\xff\"}", "application/json"), 400,
         "ill-formed UTF-8");
  auto hops =
      client.Post("/solve", "{\"pointer\": \"hops/nothing\", \"values\": []}", "application/json");
  ASSERT_TRUE(hops);
  EXPECT_EQ(hops->status, 404);
  EXPECT_NE(hops->body.find("names no gproj component"), std::string::npos);
  EXPECT_TRUE(server.Alive());
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, AnotherHostNeedsATokenAndEveryRequestCarriesIt) {
  ServerProcess open_host({"--host", "0.0.0.0"});
  EXPECT_EQ(open_host.port(), 0);
  EXPECT_NE(open_host.first_line().find("--host: serving on 0.0.0.0 (not a loopback address) "
                                        "needs --token"),
            std::string::npos)
      << open_host.first_line();
  EXPECT_EQ(open_host.Wait(), 1);
  ServerProcess blank_token({"--host", "0.0.0.0", "--token", "  "});
  EXPECT_EQ(blank_token.port(), 0);
  EXPECT_NE(blank_token.first_line().find("--token: must be at least 8 characters"),
            std::string::npos)
      << blank_token.first_line();
  EXPECT_EQ(blank_token.Wait(), 1);

  ServerProcess server({"--token", "s3cret-token"});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  auto none = client.Get("/api/schema");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  EXPECT_NE(none->body.find("needs its token"), std::string::npos);
  auto wrong = client.Get("/api/schema", {{"Authorization", "Bearer s3cret-toke"}});
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 401);
  auto bearer = client.Get("/api/schema", {{"Authorization", "Bearer s3cret-token"}});
  ASSERT_TRUE(bearer);
  EXPECT_EQ(bearer->status, 200);
  auto key = client.Get("/hops", {{"RhinoComputeKey", "s3cret-token"}});
  ASSERT_TRUE(key);
  EXPECT_EQ(key->status, 200);
  auto query = client.Get("/api/schema?token=s3cret-token");
  ASSERT_TRUE(query);
  EXPECT_EQ(query->status, 200);
  // The web app's own files load without it (a page's module imports carry no token); what the
  // service holds does not.
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  auto examples = client.Get("/api/examples");
  ASSERT_TRUE(examples);
  EXPECT_EQ(examples->status, 401);
  auto meshes = client.Post("/api/meshes", "{\"obj\": \"v 0 0 0\"}", "application/json");
  ASSERT_TRUE(meshes);
  EXPECT_EQ(meshes->status, 401);
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, RunsBeyondTheQueueAreRefusedWith429) {
  ServerProcess server({"--max-runs", "1", "--max-queued", "1"});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  const std::string running = Submit(client, SlowRequest(41));
  const std::string queued = Submit(client, SlowRequest(41));
  int status = 0;
  const std::string refused = Post(client, "/api/runs", SlowRequest(41), &status);
  EXPECT_EQ(status, 429);
  EXPECT_NE(refused.find("the service is busy: 1 runs are running and 1 queued"), std::string::npos)
      << refused;
  // The queued run is cancelled before it starts; the running one stops.
  auto cancel = client.Delete(("/api/runs/" + queued).c_str());
  ASSERT_TRUE(cancel);
  EXPECT_EQ(nlohmann::json::parse(cancel->body).at("status"), "cancelled");
  cancel = client.Delete(("/api/runs/" + running).c_str());
  ASSERT_TRUE(cancel);
  EXPECT_EQ(AwaitRun(client, running).at("status"), "cancelled");
  EXPECT_EQ(Submit(client, PlanarizeRequest(GridMesh())).size(), 16u);  // room again
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, StreamsNeverTakeEveryConnection) {
  ServerProcess server({"--connections", "8"});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  const std::string id = Submit(client, SlowRequest(41));
  std::vector<int> streams;
  for (int i = 0; i < 4; ++i) streams.push_back(OpenStream(server.port(), id));
  for (int fd : streams) EXPECT_GE(fd, 0);
  auto fifth = client.Get(("/api/runs/" + id + "/events").c_str());
  ASSERT_TRUE(fifth);
  EXPECT_EQ(fifth->status, 429);
  EXPECT_NE(fifth->body.find("4 event streams are open"), std::string::npos) << fifth->body;
  // Requests are still served, and the run can be cancelled.
  auto status = client.Get(("/api/runs/" + id).c_str());
  ASSERT_TRUE(status);
  EXPECT_EQ(status->status, 200);
  auto cancel = client.Delete(("/api/runs/" + id).c_str());
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 200);
  for (int fd : streams)
    if (fd >= 0) close(fd);
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, HopsSolveReturnsThePlanarPoints) {
  ServerProcess server({});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  auto list = client.Get("/hops");
  ASSERT_TRUE(list);
  const nlohmann::json components = nlohmann::json::parse(list->body);
  ASSERT_TRUE(components.is_array());
  bool listed = false;
  for (const nlohmann::json& c : components) listed = listed || c.at("Uri") == "/hops/planarize";
  EXPECT_TRUE(listed);
  auto description = client.Get("/hops/planarize");
  ASSERT_TRUE(description);
  EXPECT_EQ(description->status, 200);
  EXPECT_EQ(description->get_header_value("Content-Type"), "application/json");
  EXPECT_TRUE(nlohmann::json::parse(description->body).is_object());

  const std::string fixture = ReadFile(std::string(GPROJ_SOURCE_DIR) +
                                       "/tests/service/fixtures/hops_planarize_noisy_grid.json");
  auto solved = client.Post("/solve", fixture, "application/json");
  ASSERT_TRUE(solved);
  ASSERT_EQ(solved->status, 200) << solved->body.substr(0, 2000);
  const nlohmann::json answer = nlohmann::json::parse(solved->body);
  EXPECT_TRUE(answer.at("errors").empty()) << answer.at("errors");
  const nlohmann::json sent = nlohmann::json::parse(fixture);
  nlohmann::json mesh = {{"vertices", nlohmann::json::array()}, {"faces", nlohmann::json::array()}};
  const nlohmann::json& ids = sent["values"][1]["InnerTree"]["{0}"];
  for (std::size_t i = 0; i < ids.size(); i += 4)
    mesh["faces"].push_back({std::stoi(ids[i]["data"].get<std::string>()),
                             std::stoi(ids[i + 1]["data"].get<std::string>()),
                             std::stoi(ids[i + 2]["data"].get<std::string>()),
                             std::stoi(ids[i + 3]["data"].get<std::string>())});
  bool converged = false;
  for (const nlohmann::json& value : answer.at("values")) {
    if (value["ParamName"] == "converged") converged = value["InnerTree"]["0"][0]["data"] == "true";
    if (value["ParamName"] != "output_points") continue;
    for (const nlohmann::json& item : value["InnerTree"]["0"]) {
      const nlohmann::json p = nlohmann::json::parse(item["data"].get<std::string>());
      mesh["vertices"].push_back({p["X"], p["Y"], p["Z"]});
    }
  }
  EXPECT_TRUE(converged);
  ASSERT_EQ(mesh["vertices"].size(), 441u);
  EXPECT_LT(MaxDiagonalGap(mesh), 1e-7);

  // A Hops error goes to "errors", one entry per output still answered.
  nlohmann::json bad = sent;
  bad["values"][7]["InnerTree"]["{0}"][0]["data"] = "75.0";
  auto refused = client.Post("/solve", bad.dump(), "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 200);
  const nlohmann::json error = nlohmann::json::parse(refused->body);
  ASSERT_EQ(error.at("errors").size(), 1u);
  EXPECT_NE(error["errors"][0].get<std::string>().find("min_angle"), std::string::npos);
  EXPECT_EQ(error.at("values").size(),
            nlohmann::json::parse(description->body).at("Outputs").size());
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, StoppingCancelsTheRunsARequestWaitsOn) {
  ServerProcess server({});
  ASSERT_GT(server.port(), 0) << server.first_line();
  nlohmann::json body = nlohmann::json::parse(ReadFile(
      std::string(GPROJ_SOURCE_DIR) + "/tests/service/fixtures/hops_planarize_noisy_grid.json"));
  body["values"][5]["InnerTree"]["{0}"][0]["data"] = "1E-300";  // a tolerance it cannot meet
  body["values"].push_back(
      {{"ParamName", "max_iterations"},
       {"InnerTree", {{"{0}", {{{"type", "System.Int32"}, {"data", "100000"}}}}}}});
  body["values"].push_back(
      {{"ParamName", "monotone"},
       {"InnerTree", {{"{0}", {{{"type", "System.Boolean"}, {"data", "false"}}}}}}});
  std::thread solve([&] {
    httplib::Client client = server.Client();
    client.Post("/solve", body.dump(), "application/json");  // answered or cut off: either
  });
  // With the solve's run going, stop: the run is cancelled, the solve answered, the server exits
  // 0 (were the run left going, Stop would wait for it and ctest's timeout would fail this).
  httplib::Client client = server.Client();
  for (bool running = false; !running;) {
    auto list = client.Get("/api/runs");
    running = list && list->body.find("\"status\":\"running\"") != std::string::npos;
    if (!running) usleep(20000);
  }
  EXPECT_EQ(server.Stop(), 0);
  solve.join();
}

TEST(ServerTest, FiftyConcurrentRunsCompleteOrAreRefusedAndMemoryStaysBounded) {
  ServerProcess server({"--max-runs", "2", "--max-queued", "24"});
  ASSERT_GT(server.port(), 0) << server.first_line();
  const nlohmann::json body = PlanarizeRequest(GridMesh(), {{"tolerance", 1e-6}});
  const long before_kb = server.ResidentKb();
  std::atomic<int> completed{0}, refused{0}, other{0};
  std::vector<std::thread> clients;
  for (int i = 0; i < 50; ++i)
    clients.emplace_back([&] {
      httplib::Client client = server.Client();
      int status = 0;
      const std::string answer = Post(client, "/api/runs", body, &status);
      if (status == 429) {
        refused += answer.find("the service is busy") != std::string::npos ? 1 : 0;
        other += answer.find("the service is busy") != std::string::npos ? 0 : 1;
        return;
      }
      if (status != 201) {
        ++other;
        ADD_FAILURE() << "status " << status << ": " << answer;
        return;
      }
      const nlohmann::json run = AwaitRun(client, nlohmann::json::parse(answer).at("id"));
      if (!run.is_null() && run.at("status") == "converged" &&
          MaxDiagonalGap(run.at("result").at("output")) < 1e-4)
        ++completed;
      else
        ++other, ADD_FAILURE() << run.dump().substr(0, 300);
    });
  for (std::thread& t : clients) t.join();
  EXPECT_EQ(completed + refused, 50);
  EXPECT_EQ(other, 0);
  EXPECT_GE(completed, 26);  // the two running and the 24 queued are always taken
  EXPECT_TRUE(server.Alive());
  const long after_kb = server.ResidentKb();
  EXPECT_LT(after_kb, before_kb + 400 * 1024) << before_kb << " kB -> " << after_kb << " kB";
  httplib::Client client = server.Client();
  auto list = client.Get("/api/runs");
  ASSERT_TRUE(list);
  EXPECT_LE(nlohmann::json::parse(list->body).at("runs").size(), 64u);
  EXPECT_EQ(server.Stop(), 0);
}

TEST(ServerTest, ServesTheWebAppTheExamplesAndReadsDroppedMeshes) {
  ServerProcess server({});
  ASSERT_GT(server.port(), 0) << server.first_line();
  httplib::Client client = server.Client();
  // The page and its packages come from web/ (app/ and node_modules/), read at start.
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("data-status=\"idle\""), std::string::npos) << page->body;
  auto three = client.Get("/vendor/three.module.js");
  ASSERT_TRUE(three);
  EXPECT_EQ(three->status, 200);
  EXPECT_NE(three->get_header_value("Content-Type").find("javascript"), std::string::npos);
  EXPECT_GT(three->body.size(), 100000u);
  // Examples are named by their main file; each carries what a run takes and a preview mesh.
  auto list = client.Get("/api/examples");
  ASSERT_TRUE(list);
  const nlohmann::json examples = nlohmann::json::parse(list->body).at("examples");
  std::vector<std::string> names;
  for (const nlohmann::json& e : examples) names.push_back(e.at("name"));
  for (const char* name :
       {"noisy_grid_21x21", "enneper_41x41_jitter3", "marionette_plan_21x21", "freeform_10x10"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  auto grid = client.Get("/api/examples/noisy_grid_21x21");
  ASSERT_TRUE(grid);
  const nlohmann::json example = nlohmann::json::parse(grid->body);
  EXPECT_EQ(example.at("problem"), "planarize");
  EXPECT_EQ(example.at("preview").at("vertices").size(), 441u);
  EXPECT_EQ(example.at("preview"), example.at("inputs").at("mesh"));
  // A B-spline example's preview is the surface sampled 4 times per control point each way
  // (10 × 10 control points: 40 × 40 quads).
  auto freeform = client.Get("/api/examples/freeform_10x10");
  ASSERT_TRUE(freeform);
  const nlohmann::json surface = nlohmann::json::parse(freeform->body);
  EXPECT_EQ(surface.at("main"), "surface");
  EXPECT_TRUE(surface.at("inputs").at("surface").contains("control_points"));
  EXPECT_EQ(surface.at("preview").at("vertices").size(), 41u * 41u);
  auto missing = client.Get("/api/examples/nothing_here");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_NE(missing->body.find("no example nothing_here (noisy_grid_21x21"), std::string::npos)
      << missing->body;
  // A dropped file is read as the readers read files: its errors name the file and line.
  auto read =
      client.Post("/api/meshes",
                  nlohmann::json({{"name", "quad.obj"},
                                  {"obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"}})
                      .dump(),
                  "application/json");
  ASSERT_TRUE(read);
  EXPECT_EQ(read->status, 200) << read->body;
  EXPECT_EQ(nlohmann::json::parse(read->body),
            nlohmann::json({{"vertices", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}},
                            {"faces", {{0, 1, 2, 3}}}}));
  auto bad = client.Post(
      "/api/meshes",
      nlohmann::json({{"name", "bad.obj"}, {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n"}}).dump(),
      "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("bad.obj:4"), std::string::npos) << bad->body;
  auto nameless =
      client.Post("/api/meshes", nlohmann::json({{"name", 3}}).dump(), "application/json");
  ASSERT_TRUE(nameless);
  EXPECT_EQ(nameless->status, 400);
  EXPECT_NE(nameless->body.find("name: expected the file's name"), std::string::npos);
  EXPECT_TRUE(server.Alive());
  EXPECT_EQ(server.Stop(), 0);
}

}  // namespace
}  // namespace gproj::service
