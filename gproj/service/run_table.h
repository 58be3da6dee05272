#pragma once
// The runs of the HTTP service: each request becomes a run with an id, queued and executed on a
// fixed set of worker threads (never on a request's thread), its records and messages kept as a
// list of events that streams can follow, cancellable at any time, bounded in time, and kept
// after it ends (the most recent ones) for its status, report and result.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gproj/service/run_request.h"

namespace gproj::service {

// queued -> running -> converged | not-converged | failed | cancelled.
enum class RunState { kQueued, kRunning, kConverged, kNotConverged, kFailed, kCancelled };
const char* RunStateName(RunState state);  // "queued", "running", "not-converged", ...
bool IsFinished(RunState state);

struct RunLimits {
  int max_running = 0;       // runs executing at once (0: the machine's cores)
  int max_queued = 32;       // runs waiting beyond those; more are refused (RunTableFull)
  int max_kept = 64;         // finished runs kept for their status and result
  double max_seconds = 600;  // a run still going after this is stopped (not-converged)
  // Iterate events (the mesh of an iterate, for a live view): at most one per this many
  // seconds, the first iteration's always, and none for meshes of more vertices than
  // max_iterate_vertices. Only the latest is kept: an earlier one's data becomes
  // {"superseded": true}.
  double iterate_interval = 0.1;
  long long max_iterate_vertices = 250'000;
};

// Submit when max_running + max_queued runs are unfinished.
class RunTableFull : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A finished run's request and result, for a re-solve.
struct FinishedRun {
  RunRequest request;
  RunResult result;
  RunState state = RunState::kFailed;
};

// A finished run's edits for a re-solve: {"moved": [{"vertex": v, "to": [x, y, z]}, ...],
// "fixed": [ids], "options": {...}} applied to its request, starting from its result: the moved
// vertices are put where asked and held, `fixed` ones added to the held, options overridden
// (null restores a default). Throws RequestError naming the field, or when the problem has no
// warm re-solve (a mesh input, fixed vertices and a result mesh of the input's connectivity).
RunRequest ResolveRequest(const FinishedRun& run, const nlohmann::json& body);

class RunTable {
 public:
  explicit RunTable(RunLimits limits);
  ~RunTable();  // cancels every run and joins the workers
  RunTable(const RunTable&) = delete;
  RunTable& operator=(const RunTable&) = delete;

  // Queues the run; returns its id (16 hex digits). Throws RunTableFull. A run re-solved from
  // `parent` (a finished run) cancels the unfinished runs re-solved from the same parent before
  // it: a new edit supersedes the stale ones (a drag sends one edit after another).
  std::string Submit(RunRequest request, const std::string& parent = "");
  // {"id", "problem", "status", "events" (count), "error" (failed runs), "report" and "result"
  // (finished runs, when `details`)}; nullopt: no such run (or no longer kept).
  std::optional<nlohmann::json> Describe(const std::string& id, bool details) const;
  // The runs kept, oldest first: [{"id", "problem", "status", "events"}].
  nlohmann::json List() const;
  // Asks the run to stop (a queued one ends at once); false: no such run or already finished.
  bool Cancel(const std::string& id);
  // The run's events from index `from` on, waiting up to `wait` when there are none yet. Each
  // event: {"event": "columns" | "record" | "message" | "end", "data": {...}}. *ended: the run
  // has finished and its last event (end) is in. False: no such run.
  bool Events(const std::string& id, std::size_t from, std::chrono::milliseconds wait,
              std::vector<nlohmann::json>* events, bool* ended) const;
  // Waits until the run ends or `wait` passes; whether it ended (false too for no such run).
  bool Wait(const std::string& id, std::chrono::milliseconds wait) const;
  // The finished run's request and result; null while it runs or when it is not kept.
  std::shared_ptr<const FinishedRun> Finished(const std::string& id) const;
  // A stream follows the run (+1) or stopped following it (-1); when the last follower leaves
  // before the run ends, the run is cancelled (its client went away).
  void Follow(const std::string& id, int change);
  // Cancels every unfinished run (the service is stopping: requests waiting on runs return).
  void CancelAll();
  int Unfinished() const;
  const RunLimits& limits() const { return limits_; }

 private:
  struct Run;
  void Work();
  void Execute(Run* run);
  void Push(Run* run, const char* event, nlohmann::json data);
  // An iterate event, replacing the data of the run's previous one.
  void PushIterate(Run* run, nlohmann::json data);
  void Finish(Run* run, RunState state);
  void EvictFinished();
  int UnfinishedLocked() const;  // with mutex_ held

  RunLimits limits_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;  // a run's events, state or the queue changed
  std::map<std::string, std::shared_ptr<Run>> runs_;
  std::deque<std::shared_ptr<Run>> queue_;
  std::deque<std::string> finished_order_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace gproj::service
