// An editing session: project file, edit history, loaded images and synthesised textures in step.
#include <sylva/folding/Session.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sylva::folding {

namespace fs = std::filesystem;

Session::Session(fs::path file, Project project) : mFile(std::move(file)), mHistory(std::move(project)) {}

std::unique_ptr<Session> Session::open(const fs::path& file, bool recover, std::string* notice) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  std::unique_ptr<Session> s(new Session(absolute, loadProject(absolute)));
  s->loadImages();
  if (recover) {
    std::string warning;
    if (std::optional<Project> recovered = recoverAutosave(absolute, &warning)) {
      s->mHistory.apply("recover autosave", -1, [&](Project& p) { p = *recovered; });
      if (notice) {
        *notice = "recovered unsaved changes from " + autosavePath(absolute).filename().string() +
                  " (undo returns to the saved file)";
      }
    } else if (notice && !warning.empty()) {
      *notice = "ignored the autosave: " + warning;
    }
  }
  return s;
}

std::unique_ptr<Session> Session::fromImages(const std::vector<fs::path>& images,
                                             const fs::path& projectFile) {
  if (images.empty()) {
    fail("fold edit: no input image");
  }
  const fs::path absolute = fs::absolute(projectFile).lexically_normal();
  Project p;
  p.baseDir = absolute.parent_path();
  for (const fs::path& image : images) {
    ImageEntry e;
    std::string id = image.stem().string();
    for (int n = 2; p.imageIndex(id) >= 0; ++n) {
      id = image.stem().string() + "-" + std::to_string(n);
    }
    e.id = id;
    const fs::path full = fs::absolute(image).lexically_normal();
    const fs::path relative = full.lexically_relative(p.baseDir);
    e.file = relative.empty() ? full : relative;
    p.images.push_back(e);
  }
  Profile motion;
  motion.id = "motion";
  motion.periodS = 2.0;
  motion.fn.type = PositionFunction::Type::Sine;
  p.profiles.push_back(motion);
  // The same checks as a file on disk.
  Project checked = parseProject(toJson(p), absolute.string());
  checked.baseDir = p.baseDir;
  std::unique_ptr<Session> s(new Session(absolute, checked));
  s->loadImages();
  // A new project is unsaved work: record it as one edit so it is dirty and autosaves.
  s->mHistory.apply("new project", -1, [](Project&) {});
  return s;
}

std::unique_ptr<Session> Session::fromMemory(Project project, ProjectImages images,
                                             const fs::path& projectFile) {
  const fs::path absolute = fs::absolute(projectFile).lexically_normal();
  std::vector<glm::ivec2> sizes;
  for (const Image& image : images.images) {
    sizes.emplace_back(image.width(), image.height());
  }
  validateAgainstImages(project, sizes, absolute.string());
  std::unique_ptr<Session> s(new Session(absolute, std::move(project)));
  s->mImages = std::move(images);
  s->mMaskKeys = maskKeys(s->project());
  s->installValidator();
  return s;
}

void Session::loadImages() {
  mImages = loadProjectImages(project(), mFile.string());
  mMaskKeys = maskKeys(project());
  installValidator();
}

void Session::installValidator() {
  mHistory.setValidator([this](const Project& candidate) {
    std::vector<glm::ivec2> sizes;
    for (std::size_t i = 0; i < candidate.images.size(); ++i) {
      const int known = project().imageIndex(candidate.images[i].id);
      if (known < 0 || static_cast<std::size_t>(known) >= mImages.images.size()) {
        return; // a new image: checked when it loads
      }
      sizes.push_back(imageSize(known));
    }
    validateAgainstImages(candidate, sizes, "edit");
  });
}

glm::ivec2 Session::imageSize(int index) const {
  const Image& image = mImages.images.at(static_cast<std::size_t>(index));
  return {image.width(), image.height()};
}

std::vector<fs::path> Session::imageFiles() const {
  std::vector<fs::path> files;
  for (const ImageEntry& e : project().images) {
    files.push_back(fs::absolute(project().resolve(e.file)).lexically_normal());
  }
  return files;
}

bool Session::stale() const {
  return !mTextures || !(mSynthesized == project());
}

std::vector<Session::MaskKey> Session::maskKeys(const Project& p) {
  std::vector<MaskKey> keys;
  for (const Zone& z : p.zones) {
    keys.push_back({z.freezeMask, z.folding.type == Folding::Type::Mask ? z.folding.mask : fs::path()});
  }
  return keys;
}

void Session::syncMasks() {
  // Freeze and fold masks are loaded per zone: reload when zones came, went or name other mask files.
  if (maskKeys(project()) != mMaskKeys) {
    mImages = loadProjectImages(project(), mFile.string());
    mMaskKeys = maskKeys(project());
  }
}

Session::Snapshot Session::snapshot() {
  syncMasks();
  return {project(), mImages};
}

Session::Update Session::synthesize(std::optional<Rect> hint, Progress* progress) {
  Update u;
  if (!stale()) {
    return u;
  }
  const auto start = std::chrono::steady_clock::now();
  const Project& now = project();
  syncMasks();
  bool full = needsFullSynthesis();
  // Zones that differ from the synthesised state (a profile index change counts: init stores it).
  std::vector<std::size_t> changed;
  for (std::size_t z = 0; !full && z < now.zones.size(); ++z) {
    if (!(mSynthesized.zones[z] == now.zones[z]) ||
        mSynthesized.profileIndex(now.zones[z].profile) != now.profileIndex(now.zones[z].profile)) {
      changed.push_back(z);
    }
  }
  // The atlas layout can only move when a changed zone lives on a cropped image (the canvas and images with
  // crop = false are packed whole): only then pack again and compare.
  const auto cropped = [&](const Project& p, const Zone& zone) {
    const int image = p.imageIndex(zone.image);
    return image != p.canvasIndex() && p.images[static_cast<std::size_t>(image)].crop;
  };
  bool layoutMayMove = false;
  for (std::size_t z : changed) {
    layoutMayMove |= cropped(mSynthesized, mSynthesized.zones[z]) || cropped(now, now.zones[z]);
  }
  Atlas atlas;
  if (!full && layoutMayMove) {
    atlas = packAtlas(now, mImages);
    full = atlas.entries != mTextures->atlas.entries || atlas.color.width() != mTextures->width() ||
           atlas.color.height() != mTextures->height();
  }

  if (full) {
    mTextures = std::make_unique<Textures>(folding::synthesize(now, mImages, progress));
    u.full = true;
    u.region = {{0, 0}, {mTextures->width(), mTextures->height()}};
  } else {
    Rect region;
    if (hint) {
      region = *hint;
    } else {
      for (std::size_t z : changed) {
        for (const Rect r :
             {zoneAtlasRect(mSynthesized, mTextures->atlas, static_cast<int>(z)),
              zoneAtlasRect(now, layoutMayMove ? atlas : mTextures->atlas, static_cast<int>(z))}) {
          region = region.empty() ? r : Rect{glm::min(region.min, r.min), glm::max(region.max, r.max)};
        }
      }
    }
    const bool hadFold = !mTextures->fold.empty();
    resynthesize(now, mImages, *mTextures, region);
    if (hadFold != !mTextures->fold.empty()) {
      u.full = true; // the extra fold layer came or went: the GPU copy needs everything
      region = {{0, 0}, {mTextures->width(), mTextures->height()}};
    }
    u.region = region;
  }
  mSynthesized = now;
  u.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return u;
}

bool Session::needsFullSynthesis() const {
  const Project& now = project();
  return !mTextures || mSynthesized.images != now.images || mSynthesized.canvas != now.canvas ||
         mSynthesized.jumpLayers != now.jumpLayers || mSynthesized.zones.size() != now.zones.size();
}

bool Session::install(Textures textures, const Project& from, const ProjectImages& images) {
  if (images.images != mImages.images) {
    return false; // the images changed on disk meanwhile: this result is for the old pixels
  }
  mTextures = std::make_unique<Textures>(std::move(textures));
  mSynthesized = from;
  return true;
}

std::size_t synthesisRows(const Project& project, const ProjectImages& images) {
  std::size_t rows = 0;
  for (const Zone& zone : project.zones) {
    const Image& image = images.images.at(static_cast<std::size_t>(project.imageIndex(zone.image)));
    double lo = 1e300;
    double hi = -1e300;
    for (const Vec2& p : zone.shape.outline()) {
      lo = std::min(lo, p.y);
      hi = std::max(hi, p.y);
    }
    const double clipped = std::clamp(std::ceil(hi), 0.0, static_cast<double>(image.height())) -
                           std::clamp(std::floor(lo), 0.0, static_cast<double>(image.height()));
    rows += static_cast<std::size_t>(std::max(0.0, clipped));
  }
  return rows;
}

void Session::reloadImages() {
  ProjectImages fresh = loadProjectImages(project(), mFile.string());
  mImages = std::move(fresh);
  mMaskKeys = maskKeys(project());
  mTextures.reset();
}

void Session::save() {
  saveEdited(mHistory, mFile);
}

void Session::saveAs(const fs::path& file) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  const fs::path dir = absolute.parent_path();
  const bool current = !stale();
  const Project& p = project();
  Project moved = p;
  auto rebase = [&](const fs::path& f) -> fs::path {
    if (f.empty() || f.is_absolute()) {
      return f;
    }
    const fs::path full = fs::absolute(p.resolve(f)).lexically_normal();
    const fs::path relative = full.lexically_relative(dir);
    return relative.empty() ? full : relative;
  };
  for (ImageEntry& e : moved.images) {
    e.file = rebase(e.file);
  }
  for (Zone& z : moved.zones) {
    z.freezeMask = rebase(z.freezeMask);
    z.folding.mask = rebase(z.folding.mask);
  }
  moved.baseDir = dir;
  if (!(moved == p)) {
    mHistory.apply("save as", -1, [&](Project& q) { q = moved; });
  }
  mFile = absolute;
  save();
  if (current) {
    mSynthesized = project(); // the same textures: only where files resolve from moved
  }
}

void Session::masksChanged(int zone) {
  mImages = loadProjectImages(project(), mFile.string());
  mMaskKeys = maskKeys(project());
  if (mTextures && zone >= 0 && static_cast<std::size_t>(zone) < mSynthesized.zones.size()) {
    mSynthesized.zones[static_cast<std::size_t>(zone)].zeroSpacing = -1.0; // differs: re-synthesise it
  }
}

void Session::autosaveNow() const {
  autosave(mHistory, mFile);
}

} // namespace sylva::folding
