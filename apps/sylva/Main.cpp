// `sylva`: the command-line entry point. Every subcommand has --help; errors print one line on stderr and
// exit with status 2 (imgdiff exits 1 when images differ).
#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>

#include <sylva/core/Progress.hpp>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <thread>
#include <unistd.h>

namespace sylva::app {

void ContextFlags::add(CLI::App& command) {
  command.add_option("--egl-platform", eglPlatform, "Headless EGL platform: auto, device or surfaceless")
      ->check(CLI::IsMember({"auto", "device", "surfaceless"}))
      ->capture_default_str();
  command.add_option("--egl-device", eglDevice, "EGL device index (-1: first that works, hardware first)")
      ->capture_default_str();
}

platform::ContextOptions ContextFlags::options() const {
  platform::ContextOptions options;
  options.eglPlatform = eglPlatform;
  options.eglDevice = eglDevice;
  return options;
}

MachineInfo machineInfo() {
  MachineInfo info;
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  info.host = host;
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      info.cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  info.cores = std::thread::hardware_concurrency();
  return info;
}

int& exitCode() {
  static int code = 0;
  return code;
}

} // namespace sylva::app

namespace {

/** Ctrl-C: long work (anything showing progress) stops cleanly, writing no partial file; otherwise quit. */
extern "C" void onInterrupt(int signal) {
  if (sylva::Progress::anyActive()) {
    sylva::Progress::cancelAll();
  } else {
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

} // namespace

int main(int argc, char** argv) {
  using namespace sylva;
  std::signal(SIGINT, onInterrupt);
  CLI::App app{"Sylva: real-time procedural nature (terrain, grass, trees, folding textures).\n"
               "Run 'sylva <command> --help' for a command's options.",
               "sylva"};
  app.set_version_flag("--version", std::string("sylva ") + SYLVA_VERSION);
  std::string logLevel = "warn";
  app.add_option("--log-level", logLevel, "Log verbosity: trace, debug, info, warn, error, off")
      ->capture_default_str();
  app.require_subcommand(1);
  app::registerInfo(app);
  app::registerRender(app);
  app::registerView(app);
  app::registerBench(app);
  app::registerImgdiff(app);
#ifdef SYLVA_HAVE_TERRAIN
  app::registerTerrain(app);
#endif
  app.parse_complete_callback([&] { log::setLevel(log::parseLevel(logLevel)); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 reports an unknown command as a missing one; name it instead.
    std::string commands;
    bool known = false;
    for (const CLI::App* command : app.get_subcommands({})) {
      commands += (commands.empty() ? "" : ", ") + command->get_name();
      known = known || (argc > 1 && command->get_name() == argv[1]);
    }
    if (argc > 1 && argv[1][0] != '-' && !known) {
      std::fprintf(stderr, "sylva: error: unknown command '%s' (commands: %s)\n", argv[1], commands.c_str());
      return 2;
    }
    std::fprintf(stderr, "sylva: error: %s (see 'sylva --help')\n", e.what());
    return 2;
  } catch (const Error& e) {
    std::fprintf(stderr, "sylva: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sylva: internal error: %s\n", e.what());
    return 3;
  } catch (...) {
    std::fprintf(stderr, "sylva: internal error: unknown exception\n");
    return 3;
  }
  return app::exitCode();
}
