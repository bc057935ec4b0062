// `sylva`: the command-line entry point. Every subcommand has --help; errors print one line on stderr and
// exit with status 2 (imgdiff exits 1 when images differ).
#include "Commands.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Progress.hpp>

#include <csignal>

#include <unistd.h>

namespace {

/**
 * Ctrl-C: long work (anything showing progress) stops cleanly and the command exits with its one-line
 * "cancelled" error, writing no output; once every output is written (markOutputsComplete) it is ignored.
 * Otherwise (and for SIGTERM) the process says so in one line, removes the temporary file of any write in
 * progress and ends as the signal asks. Everything here is async-signal-safe.
 */
extern "C" void onInterrupt(int signal) {
  if (signal == SIGINT && sylva::outputsComplete()) {
    return; // every output is written: finish normally
  }
  if (signal == SIGINT && sylva::Progress::anyActive()) {
    sylva::Progress::cancelAll();
    return;
  }
  static const char kInterrupted[] = "sylva: interrupted; unfinished output files were removed\n";
  static const char kTerminated[] = "sylva: terminated; unfinished output files were removed\n";
  const char* text = signal == SIGINT ? kInterrupted : kTerminated;
  const std::size_t size = signal == SIGINT ? sizeof(kInterrupted) - 1 : sizeof(kTerminated) - 1;
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, size);
  sylva::removeTemporaryFilesForSignal();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

} // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  const auto cli = sylva::app::makeCli();
  return sylva::app::runCli(*cli, argc, argv);
}
