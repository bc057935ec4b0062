#pragma once

#include <sylva/platform/GlContext.hpp>

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>

namespace sylva::app {

/** Options shared by every command that creates a GL context. */
struct ContextFlags {
  std::string eglPlatform = "auto";
  int eglDevice = -1;
  void add(CLI::App& command);
  platform::ContextOptions options() const;
};

/**
 * Adds the options of a scripted window run (tests, screenshots): --frames N (quit after N frames),
 * --screenshot F (save the last frame), --fixed-step S (advance time S seconds per frame).
 */
void addScriptedWindowOptions(CLI::App& command, int& frames, std::string& screenshot, double& fixedStep);

/** Each register* adds one subcommand whose callback runs it; errors are thrown as sylva::Error. */
void registerInfo(CLI::App& app);
void registerRender(CLI::App& app);
void registerView(CLI::App& app);
void registerBench(CLI::App& app);
void registerImgdiff(CLI::App& app);
void registerTerrain(CLI::App& app);
/** `sylva tree generate|info|species|pieces|import-piece` (trees from interlocking pieces, docs/trees.md). */
void registerTree(CLI::App& app);
/** `sylva fold synth|render|view|export-shader|info` (folding textures, docs/folding.md). */
void registerFold(CLI::App& app);
/** `sylva capture [synth]` (grass blade capture, docs/capture.md). */
void registerCapture(CLI::App& app);
/** `sylva texsynth quilt|tiles|wang` (image quilting and tile sets, docs/texsynth.md). */
void registerTexsynth(CLI::App& app);
/** `sylva scene check`: every error of scene files, without rendering (CmdSceneCheck.cpp). */
void registerScene(CLI::App& app);

/** `sylva farm submit|each|status|wait|resubmit|cancel`: Slurm job arrays (docs/farm.md, CmdFarm.cpp). */
void registerFarm(CLI::App& app);

/** The whole `sylva` command line: every subcommand registered, callbacks running the commands. */
struct Cli {
  std::unique_ptr<CLI::App> app;
  std::string logLevel = "warn";
};
std::unique_ptr<Cli> makeCli();
/** Parses and runs; returns the process exit status (errors: one line on stderr, 2; internal errors: 3). */
int runCli(Cli& cli, int argc, const char* const* argv);

/** Exit code a command asks for (imgdiff: 1 when images differ); 0 by default. */
int& exitCode();

/** The git revision the program was built from (`git describe --always --dirty`), or "unknown". */
const char* gitRevision();

/** "sylva 0.2.0 (git d9afbf0ab1c2)": what `sylva --version` prints. */
std::string versionLine();

} // namespace sylva::app
