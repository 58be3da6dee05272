#pragma once
// A real `gproj serve` process for the service's tests: started on a free port (--port 0, read
// off its first line), reached with cpp-httplib's client, stopped with SIGTERM (it must exit 0).

#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj::service {

class ServerProcess {
 public:
  // Starts `gproj serve --port 0 ARGS`; port() is 0 when it did not start (its first line is in
  // first_line(), e.g. an error).
  explicit ServerProcess(const std::vector<std::string>& args) {
    int out[2];
    if (pipe(out) != 0) return;
    std::vector<std::string> all = {GPROJ_BINARY, "serve", "--port", "0"};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> environment = ServerEnvironment();
    std::vector<char*> envp;
    for (std::string& e : environment) envp.push_back(e.data());
    envp.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      dup2(out[1], STDERR_FILENO);
      close(out[0]);
      close(out[1]);
      execve(GPROJ_BINARY, argv.data(), envp.data());
      _exit(127);
    }
    close(out[1]);
    output_ = fdopen(out[0], "r");
    char line[1024] = {};
    if (output_ && std::fgets(line, sizeof line, output_)) first_line_ = line;
    const std::string marker = "listening on http://127.0.0.1:";
    const std::size_t at = first_line_.find(marker);
    if (at != std::string::npos) port_ = std::stoi(first_line_.substr(at + marker.size()));
  }
  ~ServerProcess() { Stop(); }

  // This process's environment for the server. Under AddressSanitizer the freed-memory
  // quarantine (256 MB by default) is cut to 16 MB, so that the server's resident memory measures
  // what the service keeps, not what the sanitizer holds back.
  static std::vector<std::string> ServerEnvironment() {
    std::vector<std::string> environment;
    std::string asan;
    for (char** e = environ; *e; ++e) {
      const std::string entry = *e;
      if (entry.rfind("ASAN_OPTIONS=", 0) == 0)
        asan = entry.substr(13);
      else
        environment.push_back(entry);
    }
#if defined(__SANITIZE_ADDRESS__)
    asan += (asan.empty() ? "" : ":") + std::string("quarantine_size_mb=16");
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    asan += (asan.empty() ? "" : ":") + std::string("quarantine_size_mb=16");
#endif
#endif
    if (!asan.empty()) environment.push_back("ASAN_OPTIONS=" + asan);
    return environment;
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // SIGTERM, then the exit code (-1: killed by a signal, e.g. a crash).
  int Stop() { return End(true); }
  // The exit code of a process that ends by itself (a refused start).
  int Wait() { return End(false); }
  int End(bool terminate) {
    if (pid_ <= 0) return exit_code_;
    if (terminate) kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (output_) std::fclose(output_);
    output_ = nullptr;
    return exit_code_;
  }
  // Whether the process is still running.
  bool Alive() const {
    return pid_ > 0 && kill(pid_, 0) == 0 && waitpid(pid_, nullptr, WNOHANG) == 0;
  }
  // Resident memory in kB (/proc/PID/status VmRSS).
  long ResidentKb() const {
    std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
  }
  int port() const { return port_; }
  const std::string& first_line() const { return first_line_; }
  httplib::Client Client() const {
    httplib::Client client("127.0.0.1", port_);
    client.set_read_timeout(120, 0);
    return client;
  }

 private:
  pid_t pid_ = -1;
  FILE* output_ = nullptr;
  std::string first_line_;
  int port_ = 0;
  int exit_code_ = -1;
};

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string ExamplePath(const std::string& name) {
  return std::string(GPROJ_SOURCE_DIR) + "/examples/data/" + name;
}

// A mesh as the service's JSON.
inline nlohmann::json MeshToJson(const PolyMesh& mesh) {
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    vertices.push_back({p[0], p[1], p[2]});
  }
  for (const auto fh : mesh.faces()) {
    nlohmann::json face = nlohmann::json::array();
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
    faces.push_back(face);
  }
  return {{"vertices", vertices}, {"faces", faces}};
}

// The largest distance between the two diagonals of a quad over the mean diagonal length: an
// independent planarity measure of a result given as vertices and quad faces.
inline double MaxDiagonalGap(const nlohmann::json& mesh) {
  double worst = 0.0;
  for (const nlohmann::json& face : mesh.at("faces")) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        p[k][c] = mesh.at("vertices")[face[k].get<int>()][c].get<double>();
    const Eigen::Vector3d d1 = p[2] - p[0], d2 = p[3] - p[1];
    const Eigen::Vector3d n = d1.cross(d2);
    const double gap = std::abs((p[1] - p[0]).dot(n)) / n.norm();
    worst = std::max(worst, gap / (0.5 * (d1.norm() + d2.norm())));
  }
  return worst;
}

// Polls GET /api/runs/ID until its status is not one of `waiting`; its JSON (null when the run
// is not found). No deadline: a run that never ends fails the test by ctest's timeout.
inline nlohmann::json AwaitStatus(httplib::Client& client, const std::string& id,
                                  const std::vector<std::string>& waiting) {
  for (;;) {
    const auto res = client.Get(("/api/runs/" + id).c_str());
    if (!res || res->status != 200) return nlohmann::json();
    nlohmann::json run = nlohmann::json::parse(res->body);
    if (std::find(waiting.begin(), waiting.end(), run.at("status")) == waiting.end()) return run;
    std::this_thread::yield();
  }
}

// The run's JSON once it has finished.
inline nlohmann::json AwaitRun(httplib::Client& client, const std::string& id) {
  return AwaitStatus(client, id, {"queued", "running"});
}

}  // namespace gproj::service
