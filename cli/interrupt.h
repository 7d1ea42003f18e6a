#pragma once
// Ctrl-C (SIGINT) for work that can keep what it has done: once keep_work_on_interrupt() is
// called, the first Ctrl-C only sets a flag that the work checks (it stops, writes what it has
// and exits 130); a second one exits at once. Before that, Ctrl-C exits at once.
#include <atomic>
#include <stdexcept>

namespace edacrt::cli {

/// The exit status of an interrupted command (128 + SIGINT, as shells report it).
constexpr int kInterruptedStatus = 130;

/// Installs the handler, unless SIGINT is ignored (a background job of a shell without job
/// control): that choice of the caller is kept.
void catch_interrupts();

/// From now on the first Ctrl-C sets interrupted() instead of exiting.
void keep_work_on_interrupt();

/// True once Ctrl-C was pressed after keep_work_on_interrupt(); a cancel flag for
/// Renderer::render_pass.
const std::atomic<bool>& interrupted();

/// Thrown by a command that stopped early at Ctrl-C, saying what it wrote: main() prints
/// "edacrt: interrupted: WHAT" and exits with kInterruptedStatus.
class Interrupted : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace edacrt::cli
