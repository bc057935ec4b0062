// The `sylva` command line as a library: every subcommand registered on one CLI11 app, and the error policy
// (one line on stderr, exit 2; internal errors exit 3). Main.cpp and the CLI fuzz target share it.
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>
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

void addScriptedWindowOptions(CLI::App& command, int& frames, std::string& screenshot, double& fixedStep) {
  command.add_option("--frames", frames, "Quit after this many frames (0: run until closed)")
      ->check(CLI::Range(0, 1000000));
  command.add_option("--screenshot", screenshot, "Save the last frame (with --frames) to this PNG");
  command
      .add_option("--fixed-step", fixedStep, "Advance time by this many seconds per frame (deterministic)")
      ->check(finiteRange(0.0, 10.0));
}

int& exitCode() {
  static int code = 0;
  return code;
}

std::string versionLine() {
  return fmt::format("sylva {} (git {})", SYLVA_VERSION, gitRevision());
}

std::unique_ptr<Cli> makeCli() {
  auto cli = std::make_unique<Cli>();
  cli->app = std::make_unique<CLI::App>(
      "Sylva: real-time procedural nature (terrain, grass, trees, folding textures).\n"
      "Run 'sylva <command> --help' for a command's options.",
      "sylva");
  CLI::App& app = *cli->app;
  app.set_version_flag("--version", versionLine());
  app.add_option("--log-level", cli->logLevel, "Log verbosity: trace, debug, info, warn, error, off")
      ->capture_default_str();
  app.require_subcommand(1);
  registerInfo(app);
  registerRender(app);
  registerView(app);
  registerBench(app);
  registerImgdiff(app);
#ifdef SYLVA_HAVE_TERRAIN
  registerTerrain(app);
#endif
#ifdef SYLVA_HAVE_TREES
  registerTree(app);
#endif
#ifdef SYLVA_HAVE_FOLDING
  registerFold(app);
#endif
#ifdef SYLVA_HAVE_CAPTURE
  registerCapture(app);
#endif
#ifdef SYLVA_HAVE_TEXSYNTH
  registerTexsynth(app);
#endif
#ifdef SYLVA_HAVE_SCENE
  registerScene(app);
  registerFarm(app);
#endif
  Cli* raw = cli.get();
  app.parse_complete_callback([raw] { log::setLevel(log::parseLevel(raw->logLevel)); });
  return cli;
}

int runCli(Cli& cli, int argc, const char* const* argv) {
  CLI::App& app = *cli.app;
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
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "sylva: error: out of memory: the input needs more memory than this process may use "
                         "(see ulimit -v; DEMs larger than memory: sylva terrain pyramid)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sylva: internal error: %s\n", e.what());
    return 3;
  } catch (...) {
    std::fprintf(stderr, "sylva: internal error: unknown exception\n");
    return 3;
  }
  return exitCode();
}

} // namespace sylva::app
