// `sylva fold edit`: Files: the path prompt, exports, editing an image in an external editor, watching files,
// autosave and motion from a reference video.
#include "internal/Editor.hpp"

namespace sylva::folding_ui {

void FoldEditor::prompt(PathPrompt::Action action, const std::string& title) {
  mPrompt.action = action;
  mPrompt.title = title;
  std::string initial;
  if (mSession) {
    const fs::path dir = mSession->file().parent_path();
    switch (action) {
    case PathPrompt::Action::SaveAs:
      initial = mSession->file().string();
      break;
    case PathPrompt::Action::ExportZones:
      initial = (dir / "zones.json").string();
      break;
    case PathPrompt::Action::ExportProfiles:
      initial = (dir / "profiles.json").string();
      break;
    case PathPrompt::Action::ExportTextures:
      initial = (dir / (mSession->file().stem().string() + "-textures")).string();
      break;
    case PathPrompt::Action::ExportGif:
      initial = (dir / (mSession->file().stem().string() + ".gif")).string();
      break;
    case PathPrompt::Action::ExportVideo:
      initial = (dir / (mSession->file().stem().string() + ".mp4")).string();
      break;
    case PathPrompt::Action::ExportSprites:
      initial = (dir / (mSession->file().stem().string() + "-sprites.png")).string();
      break;
    case PathPrompt::Action::ExportShader:
      initial = (dir / (mSession->file().stem().string() + "-shader")).string();
      break;
    case PathPrompt::Action::ExportWeb:
      initial = (dir / (mSession->file().stem().string() + ".html")).string();
      break;
    default:
      initial = dir.string() + "/";
      break;
    }
  } else {
    initial = fs::current_path().string() + "/";
  }
  std::snprintf(mPrompt.path, sizeof(mPrompt.path), "%s", initial.c_str());
  mPrompt.open = true;
}

void FoldEditor::runPrompt(const std::string& path) {
  const fs::path p(path);
  try {
    switch (mPrompt.action) {
    case PathPrompt::Action::Open:
      openProject(p, true);
      break;
    case PathPrompt::Action::NewFromImage: {
      std::vector<fs::path> images;
      std::size_t start = 0;
      while (start < path.size()) {
        const std::size_t end = path.find(';', start);
        const std::string part = path.substr(start, end == std::string::npos ? end : end - start);
        if (!part.empty()) {
          images.emplace_back(part);
        }
        start = end == std::string::npos ? path.size() : end + 1;
      }
      if (images.empty()) {
        fail("new project: give one or more image files (separated by ';')");
      }
      newProject(images, defaultProjectFile(images.front()));
      break;
    }
    case PathPrompt::Action::SaveAs:
      mSession->saveAs(p);
      mRecent.add(mSession->file());
      mRecent.save();
      setStatus("saved as " + mSession->file().string(), false);
      break;
    case PathPrompt::Action::ImportZones:
      importZones(mSession->history(), loadJsonFile(p), p.string());
      setStatus("imported zones from " + p.string(), false);
      break;
    case PathPrompt::Action::ExportZones: {
      std::vector<int> all(mSession->project().zones.size());
      for (std::size_t i = 0; i < all.size(); ++i) {
        all[i] = static_cast<int>(i);
      }
      saveJsonFile(p, exportZones(mSession->project(), mZone >= 0 ? std::vector<int>{mZone} : all));
      setStatus("exported " + std::string(mZone >= 0 ? "the selected zone" : "all zones") + " to " +
                    p.string(),
                false);
      break;
    }
    case PathPrompt::Action::ImportProfiles:
      importProfiles(mSession->history(), loadJsonFile(p), p.string());
      setStatus("imported profiles from " + p.string(), false);
      break;
    case PathPrompt::Action::ExportProfiles:
      saveJsonFile(p, exportProfiles(mSession->project()));
      setStatus("exported profiles to " + p.string(), false);
      break;
    case PathPrompt::Action::MaskImport: {
      requireZone();
      Zone z = mSession->project().zones[static_cast<std::size_t>(mZone)];
      z.folding.type = Folding::Type::Mask;
      const fs::path full = fs::absolute(p);
      const fs::path rel = full.lexically_relative(mSession->file().parent_path());
      z.folding.mask = rel.empty() ? full : rel;
      z.folding.polygons.clear();
      replaceZone(mSession->history(), mZone, z, "import alpha mask");
      setStatus("fold region of '" + z.id + "' from " + p.string(), false);
      break;
    }
    case PathPrompt::Action::Video:
      loadFlowVideo(p);
      break;
    default:
      runExport(mPrompt.action, p);
      break;
    }
  } catch (const Error& e) {
    setStatus(e.what(), true);
  }
}

void FoldEditor::requireZone() const {
  if (mZone < 0) {
    fail("select a zone first (or draw one with R)");
  }
}

std::vector<Image> FoldEditor::frames(double fps) {
  synthesizeNow();
  const Textures& tex = *mSession->textures();
  const double period = loopPeriod(mSession->project().profiles).seconds;
  const int count = std::clamp(static_cast<int>(std::lround(period * fps)), 1, 600);
  std::vector<Image> out;
  const AtlasEntry& entry = tex.atlas.entries[static_cast<std::size_t>(mImage)];
  for (int i = 0; i < count; ++i) {
    out.push_back(cropToEntry(renderFrame(tex, mSession->project().profiles, mSession->project().jumpLayers,
                                          i / fps, std::max(1u, std::thread::hardware_concurrency())),
                              entry));
  }
  return out;
}

void FoldEditor::runExport(PathPrompt::Action action, const fs::path& p) {
  if (!mSession) {
    return;
  }
  synthesizeNow();
  const Textures& tex = *mSession->textures();
  switch (action) {
  case PathPrompt::Action::ExportTextures:
    saveTextures(p, mSession->project(), tex);
    break;
  case PathPrompt::Action::ExportGif:
    writeGif(p, frames(mExportFps), static_cast<int>(std::lround(100.0 / mExportFps)));
    break;
  case PathPrompt::Action::ExportVideo:
    writeVideo(p, frames(mExportFps), mExportFps);
    break;
  case PathPrompt::Action::ExportSprites: {
    fs::path json = p;
    json.replace_extension(".json");
    writeSpriteSheet(p, json, frames(mExportFps), 8, mExportFps);
    break;
  }
  case PathPrompt::Action::ExportShader:
    saveTextures(p, mSession->project(), tex);
    folding::gpu::exportShader(p, mLibrary, mSession->project(),
                               folding::gpu::encodedInfo(mSession->project(), tex));
    break;
  case PathPrompt::Action::ExportWeb:
    folding::gpu::writeWebPreview(p, mLibrary, mSession->project(), tex);
    break;
  default:
    return;
  }
  setStatus("exported " + p.string(), false);
}

void FoldEditor::editImageExternally() {
  if (!mSession) {
    return;
  }
  const fs::path file = mSession->imageFiles().at(static_cast<std::size_t>(mImage));
  std::string why;
  const std::optional<std::vector<std::string>> command = imageEditorCommand(file, &why);
  if (!command) {
    setStatus(why, true);
    return;
  }
  std::string error;
  if (launchDetached(*command, &error) <= 0) {
    setStatus(error, true);
    return;
  }
  setStatus(fmt::format("opened {} in {}; saving it there reloads it here", file.filename().string(),
                        command->front()),
            false);
}

void FoldEditor::pollFiles() {
  reapChildren();
  if (!mSession || mShell.clock().time() - mLastPoll < 0.5) {
    return;
  }
  mLastPoll = mShell.clock().time();
  const std::vector<fs::path> changed = mWatcher.poll();
  if (changed.empty()) {
    return;
  }
  try {
    mSession->reloadImages();
    retireImageTextures();
    for (const Image& image : mSession->images().images) {
      mImageTextures.push_back(imageTexture(image));
    }
    mUploaded = false;
    refresh();
    setStatus(fmt::format("reloaded {} (changed on disk); zones and anchors kept", changed.front().string()),
              false);
  } catch (const Error& e) {
    setStatus(e.what(), true);
  }
}

void FoldEditor::autosaveTick() {
  if (!mSession || mOptions.autosaveSeconds <= 0.0 || !mSession->history().dirty()) {
    mLastAutosave = mShell.clock().time();
    return;
  }
  if (mShell.clock().time() - mLastAutosave >= mOptions.autosaveSeconds) {
    mLastAutosave = mShell.clock().time();
    try {
      mSession->autosaveNow();
    } catch (const Error& e) {
      setStatus(e.what(), true);
    }
  }
}

void FoldEditor::loadFlowVideo(const fs::path& p) {
  FlowPanel& f = mFlow;
  f.clip = loadVideo(p, 600);
  f.file = p.string();
  f.frameA = 0;
  f.frameB = std::min<int>(1, static_cast<int>(f.clip.frames.size()) - 1);
  f.suggestions.clear();
  f.flow = {};
  f.open = true;
  updateFlowThumbs();
  setStatus(fmt::format("{}: {} frames {}×{}", p.filename().string(), f.clip.frames.size(), f.clip.size.x,
                        f.clip.size.y),
            false);
}

void FoldEditor::updateFlowThumbs() {
  if (mFlow.clip.frames.empty()) {
    return;
  }
  replaceTexture(mFlow.thumbA, imageTexture(mFlow.clip.frames[static_cast<std::size_t>(mFlow.frameA)]));
  replaceTexture(mFlow.thumbB, imageTexture(mFlow.clip.frames[static_cast<std::size_t>(mFlow.frameB)]));
}

void FoldEditor::computeSuggestions() {
  FlowPanel& f = mFlow;
  requireZone();
  const Image& a = f.clip.frames.at(static_cast<std::size_t>(f.frameA));
  const Image& b = f.clip.frames.at(static_cast<std::size_t>(f.frameB));
  const FlowMethod method = f.method == 0 ? FlowMethod::Dis : FlowMethod::Farneback;
  f.flow = computeFlow(a, b, method);
  const FlowField backward = computeFlow(b, a, method);
  f.options.mapping = f.mapImage ? FlowSuggestOptions::Mapping::Image : FlowSuggestOptions::Mapping::Zone;
  const Zone& zone = mSession->project().zones[static_cast<std::size_t>(mZone)];
  const int image = mSession->project().imageIndex(zone.image);
  f.suggestions =
      suggestAnchors(f.flow, zone.shape, mSession->imageSize(image), f.options, &backward, &f.stats);
  f.zone = mZone;
  replaceTexture(f.flowTex, imageTexture(flowPicture(f.flow)));
  setStatus(fmt::format("{} anchors suggested (mean flow {:.2f} px); Accept adds them to '{}'",
                        f.suggestions.size(), f.flow.meanMagnitude(), zone.id),
            false);
}

} // namespace sylva::folding_ui
