#pragma once
// A stop asked for while a run is in a stage that sends no iteration records (paneling, a jet
// fit, an integer-grid map): such stages take a poll (`StopPoll`, null: never), ask it between
// their steps and throw RunStopped when it says yes; the run then ends USER_ABORT
// (RunContext::stop_requested is the poll a front end gives: Ctrl-C, a cancelled request).

#include <functional>
#include <stdexcept>
#include <string>

namespace gproj {

using StopPoll = std::function<bool()>;

class RunStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws RunStopped("the run was stopped during <stage>") when `stop` says so.
inline void PollStop(const StopPoll& stop, const char* stage) {
  if (stop && stop()) throw RunStopped(std::string("the run was stopped during ") + stage);
}

}  // namespace gproj
