#include "gproj/service/run_table.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "gproj/problems/run/report_json.h"

namespace gproj::service {

const char* RunStateName(RunState state) {
  switch (state) {
    case RunState::kQueued:
      return "queued";
    case RunState::kRunning:
      return "running";
    case RunState::kConverged:
      return "converged";
    case RunState::kNotConverged:
      return "not-converged";
    case RunState::kFailed:
      return "failed";
    case RunState::kCancelled:
      return "cancelled";
  }
  return "failed";
}

bool IsFinished(RunState state) {
  return state != RunState::kQueued && state != RunState::kRunning;
}

struct RunTable::Run {
  std::string id;
  std::string problem;
  RunRequest request;
  RunState state = RunState::kQueued;
  std::vector<nlohmann::json> events;
  std::atomic<bool> cancel{false};
  bool timed_out = false;
  int followers = 0;
  std::string parent;     // the run it was re-solved from
  std::string error;      // why a run failed before its report (bad input)
  nlohmann::json report;  // of a finished run (null when it failed before one)
  nlohmann::json result;  // of a finished run
  std::shared_ptr<FinishedRun> finished;
  std::size_t last_iterate = 0;  // index of the last iterate event + 1 (0: none yet)
  std::chrono::steady_clock::time_point last_iterate_time;
};

namespace {

std::string NewId() {
  static std::mutex mutex;
  static std::random_device device;
  static std::mt19937_64 engine(
      (static_cast<std::uint64_t>(device()) << 32) ^ device() ^
      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
  std::lock_guard<std::mutex> lock(mutex);
  char id[17];
  std::snprintf(id, sizeof id, "%016llx", static_cast<unsigned long long>(engine()));
  return id;
}

const char* MessageKind(RunMessage::Kind kind) {
  switch (kind) {
    case RunMessage::Kind::kHeadline:
      return "headline";
    case RunMessage::Kind::kWarning:
      return "warning";
    default:
      return "info";
  }
}

}  // namespace

RunTable::RunTable(RunLimits limits) : limits_(limits) {
  if (limits_.max_running <= 0)
    limits_.max_running = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  limits_.max_queued = std::max(0, limits_.max_queued);
  limits_.max_kept = std::max(1, limits_.max_kept);
  for (int i = 0; i < limits_.max_running; ++i) workers_.emplace_back([this] { Work(); });
}

RunTable::~RunTable() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    for (auto& [id, run] : runs_) run->cancel = true;
  }
  changed_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

std::string RunTable::Submit(RunRequest request, const std::string& parent) {
  auto run = std::make_shared<Run>();
  run->id = NewId();
  run->problem = request.spec->name;
  run->request = std::move(request);
  run->parent = parent;
  if (!parent.empty()) {
    std::vector<std::string> stale;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& [id, other] : runs_)
        if (other->parent == parent && !IsFinished(other->state)) stale.push_back(id);
    }
    for (const std::string& id : stale) Cancel(id);
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (UnfinishedLocked() >= limits_.max_running + limits_.max_queued)
      throw RunTableFull("the service is busy: " + std::to_string(limits_.max_running) +
                         " runs are running and " + std::to_string(limits_.max_queued) +
                         " queued; try again when one has finished");
    runs_[run->id] = run;
    queue_.push_back(run);
  }
  changed_.notify_all();
  return run->id;
}

int RunTable::Unfinished() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return UnfinishedLocked();
}

void RunTable::CancelAll() {
  std::vector<std::string> ids;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [id, run] : runs_)
      if (!IsFinished(run->state)) ids.push_back(id);
  }
  for (const std::string& id : ids) Cancel(id);
}

int RunTable::UnfinishedLocked() const {
  int count = 0;
  for (const auto& [id, run] : runs_) count += IsFinished(run->state) ? 0 : 1;
  return count;
}

std::optional<nlohmann::json> RunTable::Describe(const std::string& id, bool details) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = runs_.find(id);
  if (it == runs_.end()) return std::nullopt;
  const Run& run = *it->second;
  nlohmann::json j = {{"id", run.id},
                      {"problem", run.problem},
                      {"status", RunStateName(run.state)},
                      {"events", run.events.size()}};
  if (!run.parent.empty()) j["from"] = run.parent;
  if (!run.error.empty()) j["error"] = run.error;
  if (details && IsFinished(run.state)) {
    j["report"] = run.report;
    j["result"] = run.result;
  }
  return j;
}

nlohmann::json RunTable::List() const {
  std::vector<std::string> ids;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& id : finished_order_) ids.push_back(id);
    for (const auto& [id, run] : runs_)
      if (!IsFinished(run->state)) ids.push_back(id);
  }
  nlohmann::json list = nlohmann::json::array();
  for (const std::string& id : ids)
    if (const auto run = Describe(id, false)) list.push_back(*run);
  return list;
}

bool RunTable::Cancel(const std::string& id) {
  std::shared_ptr<Run> run;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = runs_.find(id);
    if (it == runs_.end() || IsFinished(it->second->state)) return false;
    run = it->second;
    run->cancel = true;
    if (run->state == RunState::kQueued) {
      queue_.erase(std::remove(queue_.begin(), queue_.end(), run), queue_.end());
      run->error = "cancelled before it started";
    } else {
      return true;  // the worker sees the flag at its next poll and finishes the run
    }
  }
  Finish(run.get(), RunState::kCancelled);
  return true;
}

bool RunTable::Events(const std::string& id, std::size_t from, std::chrono::milliseconds wait,
                      std::vector<nlohmann::json>* events, bool* ended) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto it = runs_.find(id);
  if (it == runs_.end()) return false;
  const std::shared_ptr<Run> run = it->second;
  changed_.wait_for(lock, wait, [&] { return run->events.size() > from || stopping_; });
  for (std::size_t i = from; i < run->events.size(); ++i) events->push_back(run->events[i]);
  *ended = IsFinished(run->state);
  return true;
}

bool RunTable::Wait(const std::string& id, std::chrono::milliseconds wait) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto it = runs_.find(id);
  if (it == runs_.end()) return false;
  const std::shared_ptr<Run> run = it->second;
  return changed_.wait_for(lock, wait, [&] { return IsFinished(run->state); });
}

std::shared_ptr<const FinishedRun> RunTable::Finished(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = runs_.find(id);
  return it == runs_.end() ? nullptr : it->second->finished;
}

void RunTable::Follow(const std::string& id, int change) {
  bool cancel = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = runs_.find(id);
    if (it == runs_.end()) return;
    Run& run = *it->second;
    run.followers += change;
    cancel = change < 0 && run.followers == 0 && !IsFinished(run.state);
  }
  if (cancel) Cancel(id);
}

void RunTable::Work() {
  for (;;) {
    std::shared_ptr<Run> run;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      run = queue_.front();
      queue_.pop_front();
      run->state = RunState::kRunning;
    }
    changed_.notify_all();
    Execute(run.get());
  }
}

void RunTable::Push(Run* run, const char* event, nlohmann::json data) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    run->events.push_back({{"event", event}, {"data", std::move(data)}});
  }
  changed_.notify_all();
}

void RunTable::PushIterate(Run* run, nlohmann::json data) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (run->last_iterate > 0) run->events[run->last_iterate - 1]["data"] = {{"superseded", true}};
    run->events.push_back({{"event", "iterate"}, {"data", std::move(data)}});
    run->last_iterate = run->events.size();
  }
  changed_.notify_all();
}

void RunTable::Execute(Run* run) {
  const ProblemSpec& spec = *run->request.spec;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(limits_.max_seconds));
  RunContext context;
  context.outputs = run->request.outputs;
  context.soft_free_start = run->request.soft_free_start;
  context.on_record = [&](const RunRecord& record) {
    Push(run, "record", RecordJson(record));
    return true;
  };
  context.on_message = [&](const RunMessage& message) {
    Push(run, "message",
         {{"kind", MessageKind(message.kind)}, {"text", SpellOptions(message.text, false)}});
  };
  context.on_columns = [&](const std::vector<std::string>& columns) {
    Push(run, "columns", {{"columns", columns}});
  };
  context.on_iterate = [&](int iteration, const PolyMesh& mesh) {
    const auto now = std::chrono::steady_clock::now();
    if (iteration < 1 || static_cast<long long>(mesh.n_vertices()) > limits_.max_iterate_vertices ||
        (run->last_iterate > 0 &&
         std::chrono::duration<double>(now - run->last_iterate_time).count() <
             limits_.iterate_interval))
      return;
    run->last_iterate_time = now;
    nlohmann::json vertices = nlohmann::json::array();
    for (const auto& v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return;
      vertices.push_back({p[0], p[1], p[2]});
    }
    PushIterate(run, {{"iteration", iteration}, {"vertices", std::move(vertices)}});
  };
  context.stop_requested = [&] {
    if (run->cancel) return true;
    if (std::chrono::steady_clock::now() < deadline) return false;
    run->timed_out = true;
    return true;
  };
  Push(run, "columns", {{"columns", spec.log_measures}});
  auto finished = std::make_shared<FinishedRun>();
  RunState state = RunState::kFailed;
  try {
    finished->result = RunProblem(spec, run->request.inputs, run->request.options, context);
    RunResult& result = finished->result;
    result.report.termination = SpellOptions(result.report.termination, false);
    if (run->timed_out && !result.report.converged && !result.report.failed)
      result.report.termination = "USER_ABORT: stopped at the service's time limit of " +
                                  OptionText(limits_.max_seconds) +
                                  " s (gproj serve --max-seconds)";
    for (const RunMessage& message : result.messages)
      Push(run, "message",
           {{"kind", MessageKind(message.kind)}, {"text", SpellOptions(message.text, false)}});
    state = result.report.failed             ? RunState::kFailed
            : result.report.converged        ? RunState::kConverged
            : run->cancel && !run->timed_out ? RunState::kCancelled
                                             : RunState::kNotConverged;
    nlohmann::json report =
        RunResultJson(spec, result, run->request.options, run->request.inputs, nullptr);
    if (!result.shortfalls.empty()) {
      nlohmann::json shortfalls = nlohmann::json::array();
      for (const std::string& s : result.shortfalls) shortfalls.push_back(SpellOptions(s, false));
      report["shortfalls"] = shortfalls;
    }
    nlohmann::json json = ResultJson(spec, result);
    std::lock_guard<std::mutex> lock(mutex_);
    run->report = std::move(report);
    run->result = std::move(json);
    if (result.report.failed) run->error = result.report.termination;
  } catch (const InputError& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    run->error = SpellOptions(e.what(), false);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    run->error = std::string("internal error: ") + e.what();
  }
  finished->request = std::move(run->request);
  finished->state = state;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    run->finished = std::move(finished);
  }
  Finish(run, state);
}

void RunTable::Finish(Run* run, RunState state) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    run->state = state;
    nlohmann::json end = {{"status", RunStateName(state)}};
    if (!run->error.empty()) end["error"] = run->error;
    if (run->report.is_object()) {
      end["termination"] = run->report.value("termination", "");
      end["iterations"] = run->report.value("iterations", 0);
      end["final"] = run->report.value("final", nlohmann::json::object());
      if (run->report.contains("tolerance_measure")) {
        end["tolerance_measure"] = run->report.at("tolerance_measure");
        end["tolerance"] = run->report.at("tolerance");
      }
    }
    run->events.push_back({{"event", "end"}, {"data", std::move(end)}});
    finished_order_.push_back(run->id);
    EvictFinished();
  }
  changed_.notify_all();
}

void RunTable::EvictFinished() {
  while (static_cast<int>(finished_order_.size()) > limits_.max_kept) {
    const auto it = runs_.find(finished_order_.front());
    // A run with a stream still attached stays until the stream has read its end.
    if (it != runs_.end() && it->second->followers > 0) break;
    if (it != runs_.end()) runs_.erase(it);
    finished_order_.pop_front();
  }
}

// A finished run's edits for a re-solve: {"moved": [{"vertex": v, "to": [x,y,z]}, ...],
// "fixed": [ids], "options": {...}, "soft_terms": false} applied to its request, starting from
// its result; soft-free (RunContext::soft_free_start) unless soft_terms is true.
RunRequest ResolveRequest(const FinishedRun& run, const nlohmann::json& body) {
  const ProblemSpec& spec = *run.request.spec;
  const OutputSpec* output = spec.WarmResolveOutput();
  if (!output)
    throw RequestError("run: " + spec.name +
                       " has no warm re-solve (it needs a mesh input, fixed vertices and a result "
                       "mesh of the input's connectivity)");
  if (run.result.report.failed || !run.result.meshes.count(output->name))
    throw RequestError("run: the run has no result to start from (it " +
                       std::string(RunStateName(run.state)) + ")");
  if (!body.is_object()) throw RequestError("request: expected a JSON object");
  for (auto it = body.begin(); it != body.end(); ++it)
    if (it.key() != "moved" && it.key() != "fixed" && it.key() != "options" &&
        it.key() != "soft_terms")
      throw RequestError(it.key() +
                         ": unknown key (a re-solve has moved, fixed, options and soft_terms)");
  if (body.contains("soft_terms") && !body.at("soft_terms").is_boolean())
    throw RequestError("soft_terms: expected true or false");
  RunRequest request = run.request;
  const int n = static_cast<int>(run.result.meshes.at(output->name).n_vertices());
  auto vertex = [n](const nlohmann::json& value, const std::string& where) {
    if (!value.is_number_integer()) throw RequestError(where + ": expected a vertex id");
    const long long v = value.get<long long>();
    if (v < 0 || v >= n)
      throw RequestError(where + ": vertex " + std::to_string(v) +
                         " is out of range (the mesh has " + std::to_string(n) + " vertices)");
    return static_cast<int>(v);
  };
  const nlohmann::json moved = body.value("moved", nlohmann::json::array());
  if (!moved.is_array()) throw RequestError("moved: expected a list of {\"vertex\", \"to\"}");
  std::vector<int> moved_ids, fixed;
  std::set<int> moved_once;
  std::vector<Eigen::Vector3d> to;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const std::string where = "moved[" + std::to_string(i) + "]";
    const nlohmann::json& edit = moved[i];
    if (!edit.is_object() || !edit.contains("vertex") || !edit.contains("to") || edit.size() != 2)
      throw RequestError(where + ": expected {\"vertex\": id, \"to\": [x, y, z]}");
    const int v = vertex(edit.at("vertex"), where + ".vertex");
    if (!moved_once.insert(v).second)
      throw RequestError(where + ".vertex: vertex " + std::to_string(v) + " is moved twice");
    const nlohmann::json& point = edit.at("to");
    if (!point.is_array() || point.size() != 3)
      throw RequestError(where + ".to: expected a point [x, y, z]");
    Eigen::Vector3d p;
    for (int c = 0; c < 3; ++c) {
      if (!point[c].is_number() || !std::isfinite(point[c].get<double>()))
        throw RequestError(where + ".to[" + std::to_string(c) + "]: expected a finite number");
      p[c] = point[c].get<double>();
    }
    moved_ids.push_back(v);
    to.push_back(p);
  }
  const nlohmann::json more = body.value("fixed", nlohmann::json::array());
  if (!more.is_array()) throw RequestError("fixed: expected a list of vertex ids");
  for (std::size_t i = 0; i < more.size(); ++i)
    fixed.push_back(vertex(more[i], "fixed[" + std::to_string(i) + "]"));
  if (body.contains("options")) {
    const nlohmann::json& options = body.at("options");
    if (!options.is_object()) throw RequestError("options: expected an object");
    for (auto it = options.begin(); it != options.end(); ++it) {
      if (it.value().is_null())
        request.options.erase(it.key());
      else
        request.options[it.key()] = it.value();
    }
    request.options = CompleteOptions(spec.options, request.options);
  }
  ApplyWarmEdit(spec, run.result.meshes.at(output->name), moved_ids, to, fixed, &request.inputs);
  request.weld = false;
  request.soft_free_start = !body.value("soft_terms", false);
  return request;
}

}  // namespace gproj::service
