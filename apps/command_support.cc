#include "apps/command_support.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

namespace fs = std::filesystem;

void CheckOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  const std::string where = option + " " + path + ": ";
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(where + "is a directory, not a file");
  fs::path directory = fs::path(path).parent_path();
  if (directory.empty()) directory = ".";
  if (!fs::is_directory(directory, ec))
    throw InputError(where + "the directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0)
    throw InputError(where + "the directory " + directory.string() + " is not writable");
}

void CheckDistinctPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& outputs) {
  const auto same = [](const std::string& a, const std::string& b) {
    // Absolute first: weakly_canonical leaves a relative path whose first element does not exist
    // relative ("o.obj" and "./o.obj" would differ).
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(a, ec), ec) ==
           fs::weakly_canonical(fs::absolute(b, ec), ec);
  };
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    if (path.empty()) continue;
    for (const auto& [input_option, input] : inputs)
      if (!input.empty() && same(path, input))
        throw InputError(option + " " + path + " is the " + input_option + " file");
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].second.empty() && same(path, outputs[j].second))
        throw InputError(outputs[j].first + " and " + option + " are the same file " + path);
  }
}

void CheckOutputPaths(const std::vector<std::pair<std::string, std::string>>& inputs,
                      const std::vector<OutputPath>& outputs) {
  std::vector<std::pair<std::string, std::string>> paths;
  for (const OutputPath& o : outputs) {
    (o.mesh ? CheckMeshOutputPath : CheckOutputPath)(o.option, o.path);
    if (!o.path.empty() && !o.extension.empty()) {
      std::string ext = fs::path(o.path).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (ext != o.extension)
        throw InputError(o.option + " " + o.path + ": the file is written as " + o.extension +
                         "; give it that extension");
    }
    paths.emplace_back(o.option, o.path);
  }
  CheckDistinctPaths(inputs, paths);
}

void CheckMeshOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  CheckOutputPath(option, path);
  try {
    CheckMeshExtension(path);
  } catch (const InputError& e) {
    throw InputError(option + " " + e.what());
  }
}

void RefuseEmptyValues(CLI::App* app) {
  const CLI::Validator non_empty(
      [](std::string& text) { return text.empty() ? "an empty value is not allowed" : ""; }, "");
  for (CLI::Option* option : app->get_options())
    if (option->get_type_size() != 0) option->check(non_empty);
  for (CLI::App* command : app->get_subcommands([](CLI::App*) { return true; }))
    RefuseEmptyValues(command);
}

namespace {
bool EndsWith(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

void IterationLog::PrintHeader() const {
  std::printf("%5s %13s", "iter", "energy");
  for (const std::string& m : measures_)
    std::printf(" %*s", std::max(15, static_cast<int>(m.size())), m.c_str());
  std::printf(" %11s %10s\n", "step", "time_s");
  std::fflush(stdout);
}

void IterationLog::Print(const RunRecord& r) const {
  std::printf("%5d %13.6e", r.iteration, r.energy);
  for (const std::string& m : measures_) {
    const int width = std::max(15, static_cast<int>(m.size()));
    const double value = m == "max_constraint" ? r.max_constraint : ValueOf(r.measures, m);
    if (EndsWith(m, "_quads"))
      std::printf(" %*.0f", width, value);
    else if (EndsWith(m, "_deg"))
      std::printf(" %*.2f", width, value);
    else
      std::printf(" %*.3e", width, value);
  }
  std::printf(" %11.3e %10.4f\n", r.step, r.seconds);
  std::fflush(stdout);
}

int ExitCodeOf(const RunReport& report) {
  if (report.failed) return kExitSolverFailure;
  return report.converged ? kExitOk : kExitNotConverged;
}

int ConcludeRun(const std::string& command, const RunReport& report, const std::string& measure,
                double tolerance, const std::vector<std::string>& written, bool interrupted) {
  std::printf("%s after %d iterations, %.3f s\n", report.termination.c_str(), report.iterations,
              report.seconds);
  const int code = ExitCodeOf(report);
  if (code == kExitSolverFailure) {
    std::fprintf(stderr, "gproj %s: solver failed (%s); nothing written\n", command.c_str(),
                 report.termination.c_str());
    return code;
  }
  std::string files;
  for (const std::string& path : written)
    if (!path.empty()) files += (files.empty() ? "" : ", ") + path;
  std::printf("wrote %s\n", files.c_str());
  if (interrupted) {
    std::fflush(stdout);
    std::fprintf(stderr,
                 "gproj %s: stopped by Ctrl-C (SIGINT); the result at the stop was written, exit "
                 "code %d\n",
                 command.c_str(), kExitInterrupted);
    return kExitInterrupted;
  }
  if (code == kExitNotConverged && measure.empty())
    std::fprintf(stderr, "gproj %s: not converged (%s); the result was written, exit code %d\n",
                 command.c_str(), report.termination.c_str(), kExitNotConverged);
  else if (code == kExitNotConverged)
    std::fprintf(stderr,
                 "gproj %s: tolerance %.1e not reached (%s %.3e); the result was written, exit "
                 "code %d\n",
                 command.c_str(), tolerance, measure.c_str(), ValueOf(report.final, measure),
                 kExitNotConverged);
  return code;
}

}  // namespace gproj
