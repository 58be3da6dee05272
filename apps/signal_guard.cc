// Keeps SIGTERM's disposition out of the libraries' hands in the gproj executable.
//
// METIS (called by CHOLMOD to order large systems) installs its own SIGTERM and SIGABRT handlers
// for the length of an ordering call: a handler that longjmps back into METIS, which then
// returns an error, and CHOLMOD goes on with another ordering. A SIGTERM sent by `timeout` or a
// batch system during the ordering of a large problem was therefore swallowed, and the run went
// on for minutes. gproj installs no SIGTERM handler itself, so it keeps the default action
// (terminate; hidden temporaries left behind are removed by the next run that writes the same
// output) by refusing every change of SIGTERM's disposition made through signal() or
// sysv_signal(). The dynamic linker binds the libraries' calls to these definitions because the
// executable exports them (see CMakeLists.txt). SIGABRT stays with METIS: it raises SIGABRT when
// it runs out of memory, and CHOLMOD then falls back to another ordering.
//
// Other signals keep the C library's semantics: BSD semantics for signal(), System V semantics
// (one-shot, not masked, not restarting) for sysv_signal().
#include <signal.h>

namespace {

sighandler_t InstallHandler(int signum, sighandler_t handler, int flags, bool mask_self) {
  struct sigaction action = {};
  struct sigaction previous = {};
  if (signum == SIGTERM) {
    if (sigaction(signum, nullptr, &previous) != 0) return SIG_ERR;
    return previous.sa_handler;
  }
  action.sa_handler = handler;
  action.sa_flags = flags;
  sigemptyset(&action.sa_mask);
  if (mask_self && sigaddset(&action.sa_mask, signum) != 0) return SIG_ERR;
  if (sigaction(signum, &action, &previous) != 0) return SIG_ERR;
  return previous.sa_handler;
}

}  // namespace

extern "C" {

sighandler_t signal(int signum, sighandler_t handler) noexcept {
  return InstallHandler(signum, handler, SA_RESTART, /*mask_self=*/true);
}

sighandler_t __sysv_signal(int signum, sighandler_t handler) noexcept {
  return InstallHandler(signum, handler, SA_RESETHAND | SA_NODEFER, /*mask_self=*/false);
}

sighandler_t sysv_signal(int signum, sighandler_t handler) noexcept {
  return __sysv_signal(signum, handler);
}

}  // extern "C"
