// Synthesis of folding textures: loading the inputs, packing the colour atlas (Algorithm 1), the init and
// jump textures (Algorithms 2 and 3) with thresholds, the 16-bit/float encodings and the debug pictures.
#include <sylva/folding/Synthesis.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/ImageHeader.hpp>
#include <sylva/core/Limits.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

namespace sylva::folding {

namespace {

/** Any image as RGBA8 (grey → RGB, missing alpha → opaque, 16-bit and float → 8-bit). */
Image toRgba8(const Image& in) {
  const Image src = in.type() == PixelType::U8 ? in : in.converted(PixelType::U8);
  Image out(src.width(), src.height(), 4, PixelType::U8);
  const auto* s = reinterpret_cast<const std::uint8_t*>(src.data());
  auto* d = reinterpret_cast<std::uint8_t*>(out.data());
  const int c = src.channels();
  const std::size_t n = static_cast<std::size_t>(src.width()) * src.height();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = s + i * c;
    std::uint8_t* q = d + i * 4;
    if (c <= 2) {
      q[0] = q[1] = q[2] = p[0];
      q[3] = c == 2 ? p[1] : 255;
    } else {
      q[0] = p[0];
      q[1] = p[1];
      q[2] = p[2];
      q[3] = c == 4 ? p[3] : 255;
    }
  }
  return out;
}

/** A mask as floats in [0, 1]: the alpha channel when there is one, else the first channel. */
std::vector<float> maskValues(const Image& image) {
  std::vector<float> mask(static_cast<std::size_t>(image.width()) * image.height());
  const int c = (image.channels() == 2 || image.channels() == 4) ? image.channels() - 1 : 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      mask[static_cast<std::size_t>(y) * image.width() + x] = image.get(x, y, c);
    }
  }
  return mask;
}

/**
 * Refuses, from its header alone (before a pixel is decoded), an image over kMaxAtlasSide per side, or of
 * another size than `expected` when one is given: a 1.2 MB PNG of 20000×20000 took 23 s and 4 GB to decode
 * before the atlas refused it. Formats readImageHeader does not read are checked after decoding, as before.
 */
void checkImageHeader(const std::filesystem::path& path, const std::string& where, const std::string& field,
                      std::optional<glm::ivec2> expected = std::nullopt) {
  std::optional<ImageHeader> header;
  try {
    header = readImageHeader(path);
  } catch (const Error& e) {
    fail("{}: {}: {}", where, field, e.what());
  }
  if (!header) {
    return;
  }
  if (header->width > kMaxAtlasSide || header->height > kMaxAtlasSide) {
    fail("{}: {}: {} is a {} of {}×{} pixels, more than the {} per side the renderers support; scale or crop "
         "it",
         where, field, path.string(), header->format, header->width, header->height, kMaxAtlasSide);
  }
  if (expected && (header->width != expected->x || header->height != expected->y)) {
    fail("{}: {}: mask is {}×{} pixels, its image is {}×{}", where, field, header->width, header->height,
         expected->x, expected->y);
  }
}

std::vector<float> loadMask(const Project& project, const std::filesystem::path& file, glm::ivec2 size,
                            const std::string& where, const std::string& field) {
  checkImageHeader(project.resolve(file), where, field, size);
  Image image;
  try {
    image = loadImage(project.resolve(file));
  } catch (const Error& e) {
    fail("{}: {}: {}", where, field, e.what());
  }
  if (image.width() != size.x || image.height() != size.y) {
    fail("{}: {}: mask is {}×{} pixels, its image is {}×{}", where, field, image.width(), image.height(),
         size.x, size.y);
  }
  return maskValues(image);
}

const FlyOverTool* flyOver(const Zone& zone) {
  for (const Tool& tool : zone.tools) {
    if (const auto* f = std::get_if<FlyOverTool>(&tool)) {
      return f;
    }
  }
  return nullptr;
}

glm::ivec2 roundVec(Vec2 v) {
  return {static_cast<int>(std::lround(v.x)), static_cast<int>(std::lround(v.y))};
}

/** The bounding box of a zone's outline, clipped to its image, as whole pixels. */
Rect zoneBox(const Zone& zone, glm::ivec2 size) {
  Vec2 lo(1e18);
  Vec2 hi(-1e18);
  for (const Vec2& p : zone.shape.outline()) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  Rect r{{static_cast<int>(std::floor(lo.x)), static_cast<int>(std::floor(lo.y))},
         {static_cast<int>(std::ceil(hi.x)), static_cast<int>(std::ceil(hi.y))}};
  r.min = glm::clamp(r.min, glm::ivec2(0), size);
  r.max = glm::clamp(r.max, glm::ivec2(0), size);
  return r;
}

/** Distance (pixels) from p to the closed polyline `outline`. */
double distanceToOutline(const std::vector<Vec2>& outline, Vec2 p) {
  double best = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec2 a = outline[i];
    const Vec2 e = outline[(i + 1) % outline.size()] - a;
    const double len2 = glm::dot(e, e);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, e) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, glm::length(p - (a + t * e)));
  }
  return best;
}

/** An upper bound of |J| over a zone (pixels): base field at the box corners plus the largest residual. */
double reachOf(const Zone& zone, Rect box, const std::vector<Anchor>& anchors) {
  double base = 0.0;
  for (Vec2 c : {Vec2(box.min), Vec2(box.max), Vec2(box.min.x, box.max.y), Vec2(box.max.x, box.min.y)}) {
    base = std::max(base, glm::length(baseJump(zone, c)));
  }
  double residual = 0.0;
  for (const Anchor& a : anchors) {
    residual = std::max(residual, glm::length(a.vector - baseJump(zone, a.position)));
  }
  return base + 2.0 * residual + 1.0;
}

} // namespace

ProjectImages loadProjectImages(const Project& project, const std::string& where) {
  ProjectImages out;
  std::vector<glm::ivec2> sizes;
  for (std::size_t i = 0; i < project.images.size(); ++i) {
    checkImageHeader(project.resolve(project.images[i].file), where, fmt::format("/atlas/images/{}/file", i));
  }
  for (std::size_t i = 0; i < project.images.size(); ++i) {
    Image image;
    try {
      image = loadImage(project.resolve(project.images[i].file));
    } catch (const Error& e) {
      fail("{}: /atlas/images/{}/file: {}", where, i, e.what());
    }
    out.images.push_back(toRgba8(image));
    sizes.emplace_back(image.width(), image.height());
  }
  validateAgainstImages(project, sizes, where);
  for (std::size_t z = 0; z < project.zones.size(); ++z) {
    const Zone& zone = project.zones[z];
    const glm::ivec2 size = sizes[static_cast<std::size_t>(project.imageIndex(zone.image))];
    out.freezeMasks.push_back(zone.freezeMask.empty() ? std::vector<float>{}
                                                      : loadMask(project, zone.freezeMask, size, where,
                                                                 fmt::format("/zones/{}/freeze_mask", z)));
    out.foldMasks.push_back(
        zone.folding.type == Folding::Type::Mask
            ? loadMask(project, zone.folding.mask, size, where, fmt::format("/zones/{}/folding/file", z))
            : std::vector<float>{});
  }
  return out;
}

Atlas packAtlas(const Project& project, const ProjectImages& images) {
  const std::size_t n = project.images.size();
  const int canvas = project.canvasIndex();
  Atlas atlas;
  atlas.entries.resize(n);
  // 1. Crops: the canvas, uncropped images and fly-over objects whole; others cover their zones' boxes
  //    grown by how far their jump paths can reach.
  std::vector<bool> used(n, false);
  std::vector<Rect> crop(n);
  std::vector<int> host(n, -1);      // fly-over objects: the image they are placed relative to
  std::vector<glm::ivec2> offset(n); // ... and where (that image's pixels)
  for (std::size_t i = 0; i < n; ++i) {
    const glm::ivec2 size(images.images[i].width(), images.images[i].height());
    atlas.entries[i].id = project.images[i].id;
    atlas.entries[i].imageSize = size;
    if (static_cast<int>(i) == canvas || !project.images[i].crop) {
      crop[i] = {{0, 0}, size};
      used[i] = true;
    }
  }
  for (std::size_t z = 0; z < project.zones.size(); ++z) {
    const Zone& zone = project.zones[z];
    const auto img = static_cast<std::size_t>(project.imageIndex(zone.image));
    const glm::ivec2 size = atlas.entries[img].imageSize;
    const Rect box = zoneBox(zone, size);
    const double reach = reachOf(zone, box, zoneAnchors(zone, images.freezeMasks[z], size));
    const auto grow = static_cast<int>(std::ceil(reach));
    Rect r{glm::max(box.min - grow, glm::ivec2(0)), glm::min(box.max + grow, size)};
    if (used[img]) {
      r = {glm::min(r.min, crop[img].min), glm::max(r.max, crop[img].max)};
    }
    crop[img] = r;
    used[img] = true;
    if (const FlyOverTool* fly = flyOver(zone)) {
      const auto obj = static_cast<std::size_t>(project.imageIndex(fly->object));
      const glm::ivec2 at = roundVec(fly->from);
      if (host[obj] >= 0 && (host[obj] != static_cast<int>(img) || offset[obj] != at)) {
        fail("/zones/{}/tools: image '{}' already flies from another place; one placement per object", z,
             fly->object);
      }
      host[obj] = static_cast<int>(img);
      offset[obj] = at;
      crop[obj] = {{0, 0}, atlas.entries[obj].imageSize};
      used[obj] = true;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) {
      crop[i] = {{0, 0}, atlas.entries[i].imageSize};
    }
    atlas.entries[i].crop = crop[i];
  }
  // 2. Groups: a host with the objects placed relative to it move as one block.
  struct Member {
    std::size_t image;
    glm::ivec2 pos; // crop's top-left in group space
  };
  std::vector<std::vector<Member>> groups;
  std::vector<int> groupOf(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (host[i] >= 0) {
      continue;
    }
    groupOf[i] = static_cast<int>(groups.size());
    groups.push_back({{i, crop[i].min}});
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (host[i] < 0) {
      continue;
    }
    const auto h = static_cast<std::size_t>(host[i]);
    if (host[h] >= 0) {
      fail("atlas: image '{}' flies over '{}', which itself flies over another image; not supported",
           project.images[i].id, project.images[h].id);
    }
    groups[static_cast<std::size_t>(groupOf[h])].push_back({i, offset[i] + crop[i].min});
  }
  struct Block {
    std::size_t group;
    Rect bounds;
  };
  std::vector<Block> blocks;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    Rect b{glm::ivec2(INT32_MAX), glm::ivec2(INT32_MIN)};
    for (const Member& m : groups[g]) {
      const Rect r{m.pos, m.pos + glm::ivec2(crop[m.image].width(), crop[m.image].height())};
      for (const Member& other : groups[g]) {
        if (other.image == m.image) {
          continue;
        }
        const Rect o{other.pos - project.gutter,
                     other.pos + glm::ivec2(crop[other.image].width(), crop[other.image].height()) +
                         project.gutter};
        if (r.min.x < o.max.x && o.min.x < r.max.x && r.min.y < o.max.y && o.min.y < r.max.y) {
          fail("atlas: image '{}' flown at ({}, {}) overlaps image '{}' (with its {} px gutter); start the "
               "fly_over outside the image",
               project.images[m.image].id, m.pos.x, m.pos.y, project.images[other.image].id, project.gutter);
        }
      }
      b.min = glm::min(b.min, r.min);
      b.max = glm::max(b.max, r.max);
    }
    blocks.push_back({g, b});
  }
  // 3. Shelf packing of the blocks, tallest first, rows about as wide as the square root of the total area.
  std::stable_sort(blocks.begin(), blocks.end(),
                   [](const Block& a, const Block& b) { return a.bounds.height() > b.bounds.height(); });
  double area = 0.0;
  int widest = 0;
  for (const Block& b : blocks) {
    area += static_cast<double>(b.bounds.width() + project.gutter) * (b.bounds.height() + project.gutter);
    widest = std::max(widest, b.bounds.width());
  }
  const int rowWidth = std::max(widest, static_cast<int>(std::ceil(std::sqrt(area))));
  glm::ivec2 cursor(0);
  int rowHeight = 0;
  glm::ivec2 extent(0);
  for (const Block& b : blocks) {
    if (cursor.x > 0 && cursor.x + b.bounds.width() > rowWidth) {
      cursor = {0, cursor.y + rowHeight + project.gutter};
      rowHeight = 0;
    }
    for (const Member& m : groups[b.group]) {
      atlas.entries[m.image].atlasPos = cursor + (m.pos - b.bounds.min);
    }
    extent = glm::max(extent, cursor + glm::ivec2(b.bounds.width(), b.bounds.height()));
    cursor.x += b.bounds.width() + project.gutter;
    rowHeight = std::max(rowHeight, b.bounds.height());
  }
  if (extent.x > kMaxAtlasSide || extent.y > kMaxAtlasSide) {
    fail("atlas: packing needs {}×{} texels, more than the {} per side the renderers support", extent.x,
         extent.y, kMaxAtlasSide);
  }
  // 4. Colour: each crop, and half the gutter around it filled with its edge pixels (bilinear reads at the
  //    edge then see the image's own colour).
  atlas.color = Image(std::max(1, extent.x), std::max(1, extent.y), 4, PixelType::U8);
  auto* dst = reinterpret_cast<std::uint8_t*>(atlas.color.data());
  const int pad = project.gutter / 2;
  for (std::size_t i = 0; i < n; ++i) {
    const AtlasEntry& e = atlas.entries[i];
    const Image& img = images.images[i];
    const auto* src = reinterpret_cast<const std::uint8_t*>(img.data());
    const Rect r = e.atlasRect();
    for (int y = std::max(0, r.min.y - pad); y < std::min(extent.y, r.max.y + pad); ++y) {
      for (int x = std::max(0, r.min.x - pad); x < std::min(extent.x, r.max.x + pad); ++x) {
        const int sx = std::clamp(x - r.min.x, 0, e.crop.width() - 1) + e.crop.min.x;
        const int sy = std::clamp(y - r.min.y, 0, e.crop.height() - 1) + e.crop.min.y;
        std::copy_n(src + (static_cast<std::size_t>(sy) * img.width() + sx) * 4, 4,
                    dst + (static_cast<std::size_t>(y) * extent.x + x) * 4);
      }
    }
  }
  return atlas;
}

double Textures::jumpMax() const {
  double m = 0.0;
  for (const Image& j : jump) {
    const std::span<const float> v = j.values<float>();
    for (std::size_t i = 0; i < v.size(); i += 4) {
      m = std::max({m, static_cast<double>(std::abs(v[i])), static_cast<double>(std::abs(v[i + 1]))});
    }
  }
  return m;
}

Rect zoneAtlasRect(const Project& project, const Atlas& atlas, int zone) {
  const Zone& z = project.zones.at(static_cast<std::size_t>(zone));
  const AtlasEntry& e = atlas.entries.at(static_cast<std::size_t>(project.imageIndex(z.image)));
  const Rect box = zoneBox(z, e.imageSize);
  return {box.min + e.origin(), box.max + e.origin()};
}

Rect anchorMoveAtlasRect(const Project& project, const Atlas& atlas, int zone, Vec2 before, Vec2 after) {
  const Rect zoneRect = zoneAtlasRect(project, atlas, zone);
  const Zone& z = project.zones[static_cast<std::size_t>(zone)];
  if (z.interp.type == Interpolation::Type::Shepard) {
    return zoneRect; // every anchor weighs on every texel
  }
  // AnchorField buckets anchors in a grid anchored at their bounding box; if the move changes that box, the
  // cells change and so the order in which far-away texels sum their anchors (last-bit differences). The
  // freeze mask's anchors are left out here: they only widen the box, so "strictly inside" stays safe.
  const AtlasEntry& e = atlas.entries.at(static_cast<std::size_t>(project.imageIndex(z.image)));
  Vec2 lo(std::numeric_limits<double>::max());
  Vec2 hi(std::numeric_limits<double>::lowest());
  for (const Anchor& a : zoneAnchors(z, {}, e.imageSize)) {
    lo = glm::min(lo, a.position);
    hi = glm::max(hi, a.position);
  }
  const auto inside = [&](Vec2 p) { return p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y; };
  if (!inside(before) || !inside(after)) {
    return zoneRect;
  }
  // Texel centres c with |c − p| < R for either position; one texel of margin for rounding.
  const double r = z.interp.radius;
  const Vec2 a = glm::floor(glm::min(before, after) - r);
  const Vec2 b = glm::ceil(glm::max(before, after) + r);
  const Rect box{e.origin() + glm::ivec2(a) - 1, e.origin() + glm::ivec2(b) + 1};
  const Rect clipped{glm::max(box.min, zoneRect.min), glm::min(box.max, zoneRect.max)};
  return clipped.empty() ? Rect{} : clipped;
}

namespace {

void resetRegion(Textures& tex, Rect region) {
  const int w = tex.width();
  float* init = tex.init.values<float>().data();
  for (int y = region.min.y; y < region.max.y; ++y) {
    for (int x = region.min.x; x < region.max.x; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
      init[i + 0] = static_cast<float>(x);
      init[i + 1] = static_cast<float>(y);
      init[i + 2] = 0.0f;
      init[i + 3] = -1.0f;
      for (Image& j : tex.jump) {
        float* p = j.values<float>().data() + i;
        p[0] = p[1] = p[2] = 0.0f;
        p[3] = 1.0f;
      }
      for (Image& f : tex.fold) {
        float* p = f.values<float>().data() + i;
        p[0] = p[1] = p[2] = p[3] = 1.0f;
      }
    }
  }
}

/** Writes the texels of zone z inside `region` (atlas pixels). Returns its statistics. */
SynthesisStats synthesizeZone(const Project& project, const ProjectImages& images, Textures& tex,
                              std::size_t z, Rect region, Progress* progress, bool writeInit) {
  const Zone& zone = project.zones[z];
  const auto img = static_cast<std::size_t>(project.imageIndex(zone.image));
  const AtlasEntry& entry = tex.atlas.entries[img];
  const glm::ivec2 size = entry.imageSize;
  const ZoneField field(zone, images.freezeMasks[z], size, hash64(project.seed ^ (z * 0x9e37ULL)));
  const Rect box = zoneBox(zone, size);
  const glm::ivec2 origin = entry.origin();
  const Rect clip{glm::max(box.min, region.min - origin), glm::min(box.max, region.max - origin)};
  SynthesisStats stats;
  stats.anchors = field.anchors().anchors().size();
  if (clip.empty()) {
    return stats;
  }
  const std::vector<Vec2> outline = zone.shape.outline();
  const auto profile = static_cast<float>(project.profileIndex(zone.profile));
  // Object folds: the object's rectangle (or its alpha where it has any) placed at round(from).
  std::vector<std::vector<Vec2>> polygons = zone.folding.polygons;
  std::vector<float> objectMask;
  glm::ivec2 objectSize(0);
  glm::ivec2 objectAt(0);
  if (zone.folding.type == Folding::Type::Object) {
    const FlyOverTool* fly = flyOver(zone);
    const Image& obj = images.images[static_cast<std::size_t>(project.imageIndex(fly->object))];
    objectSize = {obj.width(), obj.height()};
    objectAt = roundVec(fly->from);
    objectMask = maskValues(obj);
    if (std::all_of(objectMask.begin(), objectMask.end(), [](float v) { return v >= 0.5f; })) {
      objectMask.clear();
      const Vec2 a(objectAt);
      const Vec2 b = a + Vec2(objectSize);
      polygons = {{a, {b.x, a.y}, b, {a.x, b.y}}};
    }
  }
  const int w = tex.width();
  float* init = tex.init.values<float>().data();
  float* jump = tex.jump[static_cast<std::size_t>(zone.layer)].values<float>().data();
  float* fold =
      tex.fold.empty() ? nullptr : tex.fold[static_cast<std::size_t>(zone.layer)].values<float>().data();
  std::atomic<std::size_t> zonePixels{0};
  std::atomic<std::size_t> folded{0};
  std::atomic<std::size_t> multi{0};
  std::mutex jumpMutex;
  double jumpMax = 0.0;
  parallelFor(
      static_cast<std::size_t>(clip.height()),
      [&](std::size_t begin, std::size_t end) {
        std::size_t localZone = 0;
        std::size_t localFolded = 0;
        std::size_t localMulti = 0;
        double localJump = 0.0;
        for (std::size_t row = begin; row < end; ++row) {
          const int py = clip.min.y + static_cast<int>(row);
          for (int px = clip.min.x; px < clip.max.x; ++px) {
            const Vec2 c(px + 0.5, py + 0.5);
            if (zone.shape.type == Shape::Type::Polygon && !insidePolygon(outline, c)) {
              continue;
            }
            ++localZone;
            Vec2 j = field.evaluate(c, static_cast<std::uint64_t>(py) * size.x + px);
            if (zone.feather > 0.0) {
              // Soft edge: J fades in with smoothstep over `feather` pixels from the zone border.
              const double f = std::clamp(distanceToOutline(outline, c) / zone.feather, 0.0, 1.0);
              j *= f * f * (3.0 - 2.0 * f);
            }
            localJump = std::max(localJump, glm::length(j));
            std::vector<Interval> intervals{{0.0, 1.0}};
            if (zone.folding.type == Folding::Type::Polygons ||
                (zone.folding.type == Folding::Type::Object && objectMask.empty())) {
              intervals = foldIntervals(polygons, c, j);
            } else if (zone.folding.type == Folding::Type::Mask) {
              intervals = foldIntervalsFromMask(images.foldMasks[z], size.x, size.y, c, j);
            } else if (zone.folding.type == Folding::Type::Object) {
              intervals =
                  foldIntervalsFromMask(objectMask, objectSize.x, objectSize.y, c - Vec2(objectAt), j);
            }
            if (intervals.empty() && zone.folding.outsideWarps) {
              intervals = {{0.0, 1.0}};
            }
            if (intervals.size() != 1 || intervals[0] != Interval{0.0, 1.0}) {
              ++localFolded;
            }
            if (intervals.size() > 1) {
              ++localMulti;
            }
            if (intervals.size() > 3) {
              // Two extra intervals fit the fold layer; the rest merge into the last one.
              intervals[2].t1 = intervals.back().t1;
              intervals.resize(3);
            }
            const glm::ivec2 a = origin + glm::ivec2(px, py);
            const std::size_t i = (static_cast<std::size_t>(a.y) * w + a.x) * 4;
            if (writeInit) {
              double dt = zone.phase + glm::dot(zone.phaseGradient, c - Vec2(box.min));
              dt -= std::floor(dt);
              init[i + 0] = static_cast<float>(a.x);
              init[i + 1] = static_cast<float>(a.y);
              init[i + 2] = static_cast<float>(dt);
              init[i + 3] = profile;
            }
            jump[i + 0] = static_cast<float>(j.x);
            jump[i + 1] = static_cast<float>(j.y);
            jump[i + 2] = intervals.empty() ? 1.0f : static_cast<float>(intervals[0].t0);
            jump[i + 3] = intervals.empty() ? 1.0f : static_cast<float>(intervals[0].t1);
            if (fold) {
              for (int e = 0; e < 2; ++e) {
                const bool has = intervals.size() > static_cast<std::size_t>(e + 1);
                fold[i + 2 * e] = has ? static_cast<float>(intervals[e + 1].t0) : 1.0f;
                fold[i + 2 * e + 1] = has ? static_cast<float>(intervals[e + 1].t1) : 1.0f;
              }
            }
          }
          if (progress) {
            progress->advance();
            if (progress->cancelled()) {
              fail("synthesis cancelled");
            }
          }
        }
        zonePixels += localZone;
        folded += localFolded;
        multi += localMulti;
        const std::lock_guard lock(jumpMutex);
        jumpMax = std::max(jumpMax, localJump);
      },
      4);
  stats.zoneJumpMax.assign(project.zones.size(), 0.0);
  stats.zoneJumpMax[z] = jumpMax;
  stats.zonePixels = zonePixels;
  stats.foldedPixels = folded;
  stats.multiInterval = multi;
  return stats;
}

/** Zones in write order: higher layers first, so the init texture ends up owned by the lowest layer. */
std::vector<std::size_t> zoneOrder(const Project& project) {
  std::vector<std::size_t> order(project.zones.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return project.zones[a].layer > project.zones[b].layer;
  });
  return order;
}

SynthesisStats synthesizeRegion(const Project& project, const ProjectImages& images, Textures& tex,
                                Rect region, Progress* progress) {
  if (tex.fold.size() != tex.jump.size()) {
    tex.fold.clear();
    for (const Image& j : tex.jump) {
      tex.fold.emplace_back(j.width(), j.height(), 4, PixelType::F32);
      const std::span<float> v = tex.fold.back().values<float>();
      std::fill(v.begin(), v.end(), 1.0f);
    }
  }
  resetRegion(tex, region);
  SynthesisStats total;
  total.zoneJumpMax.assign(project.zones.size(), 0.0);
  for (std::size_t z : zoneOrder(project)) {
    const SynthesisStats s = synthesizeZone(project, images, tex, z, region, progress, true);
    total.zoneJumpMax[z] = s.zoneJumpMax.empty() ? 0.0 : s.zoneJumpMax[z];
    total.anchors += s.anchors;
    total.zonePixels += s.zonePixels;
    total.foldedPixels += s.foldedPixels;
    total.multiInterval += s.multiInterval;
  }
  return total;
}

} // namespace

Textures synthesize(const Project& project, const ProjectImages& images, Progress* progress,
                    SynthesisStats* stats) {
  Textures tex;
  tex.atlas = packAtlas(project, images);
  const int w = tex.atlas.color.width();
  const int h = tex.atlas.color.height();
  const std::size_t layers = project.jumpLayers.size() - 1;
  // Float textures: init, and per layer jump and (possibly) fold, 16 bytes a texel each, plus a frame.
  const std::size_t bytesPerTexel = 16 * (1 + 2 * layers) + 8;
  const std::size_t need = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * bytesPerTexel;
  if (const std::optional<std::size_t> available = availableMemoryBytes(); available && need > *available) {
    fail("atlas: {}×{} texels need about {:.1f} GiB to synthesise ({} bytes a texel), {:.1f} GiB is "
         "available; "
         "crop or scale the input images",
         w, h, static_cast<double>(need) / (1u << 30), bytesPerTexel,
         static_cast<double>(*available) / (1u << 30));
  }
  tex.init = Image(w, h, 4, PixelType::F32);
  for (std::size_t l = 0; l < layers; ++l) {
    tex.jump.emplace_back(w, h, 4, PixelType::F32);
  }
  const SynthesisStats s = synthesizeRegion(project, images, tex, {{0, 0}, {w, h}}, progress);
  if (s.multiInterval == 0) {
    tex.fold.clear(); // no texel needs a second fold interval: no extra layer
  }
  if (stats) {
    *stats = s;
  }
  return tex;
}

namespace {
/** The largest distance from a texel centre of the zone to its outline, pixels (the zone's inradius). */
double zoneDepth(const Zone& zone) {
  const std::vector<Vec2> outline = zone.shape.outline();
  const Rect box = zoneBox(zone, glm::ivec2(std::numeric_limits<int>::max() / 2));
  const int step = std::max(1, std::max(box.width(), box.height()) / 256);
  double depth = 0.0;
  for (int y = box.min.y; y < box.max.y; y += step) {
    for (int x = box.min.x; x < box.max.x; x += step) {
      const Vec2 c(x + 0.5, y + 0.5);
      if (zone.shape.type == Shape::Type::Rect || insidePolygon(outline, c)) {
        depth = std::max(depth, distanceToOutline(outline, c));
      }
    }
  }
  return depth;
}
} // namespace

std::vector<std::string> stillZoneWarnings(const Project& project, const SynthesisStats& stats) {
  std::vector<std::string> warnings;
  for (std::size_t z = 0; z < project.zones.size() && z < stats.zoneJumpMax.size(); ++z) {
    const Zone& zone = project.zones[z];
    const auto translate = std::find_if(zone.tools.begin(), zone.tools.end(), [](const Tool& t) {
      return std::holds_alternative<TranslateTool>(t);
    });
    const std::string where = fmt::format("/zones/{} ('{}')", z, zone.id);
    if (translate != zone.tools.end() && zone.zeroBoundary) {
      // The translate is a base jump; the anchors carry residuals. Zero anchors on the border have residual
      // +T, so wherever a border anchor is within R the interpolated residual pulls J back towards 0: when
      // every texel is within R of the border the translate is cancelled almost everywhere.
      const double depth = zoneDepth(zone);
      if (zone.interp.radius >= depth) {
        const Vec2 v = std::get<TranslateTool>(*translate).v;
        warnings.push_back(fmt::format("{}: its zone_boundary zero anchors are within R = {:g} px of every "
                                       "texel (at most {:.0f} px from "
                                       "the border), so they cancel the translate [{:g}, {:g}] almost "
                                       "everywhere (largest motion in the zone: "
                                       "{:.2f} px): give R below {:.0f} px, or add points inside the zone",
                                       where, zone.interp.radius, depth, v.x, v.y, stats.zoneJumpMax[z],
                                       std::max(1.0, std::floor(depth))));
        continue;
      }
    }
    const bool asksForMotion = std::any_of(zone.tools.begin(), zone.tools.end(), [](const Tool& t) {
      return !std::holds_alternative<ZeroTool>(t);
    });
    if (asksForMotion && stats.zoneJumpMax[z] < kStillZonePx) {
      warnings.push_back(
          fmt::format("{}: moves at most {:.2f} px although it has tools that move; they cancel out", where,
                      stats.zoneJumpMax[z]));
    }
  }
  return warnings;
}

void resynthesize(const Project& project, const ProjectImages& images, Textures& textures, Rect region) {
  region.min = glm::max(region.min, glm::ivec2(0));
  region.max = glm::min(region.max, glm::ivec2(textures.width(), textures.height()));
  if (region.empty()) {
    return;
  }
  const bool hadFold = !textures.fold.empty();
  const SynthesisStats stats = synthesizeRegion(project, images, textures, region, nullptr);
  if (!hadFold && stats.multiInterval == 0) {
    textures.fold.clear(); // as a full synthesis: no extra layer unless a texel needs one
  }
}

// ---------------------------------------------------------------------------------------------------------
// Encodings

std::uint16_t encodeJump(double j, double jumpMax) {
  if (jumpMax <= 0.0) {
    return 32767;
  }
  return static_cast<std::uint16_t>(std::clamp(32767.0 + std::round(32767.0 * j / jumpMax), 0.0, 65534.0));
}

double decodeJump(std::uint16_t v, double jumpMax) {
  return (static_cast<double>(v) - 32767.0) / 32767.0 * jumpMax;
}

std::uint16_t encodeUnit(double t) {
  return static_cast<std::uint16_t>(std::clamp(std::round(t * 65535.0), 0.0, 65535.0));
}

double decodeUnit(std::uint16_t v) {
  return static_cast<double>(v) / 65535.0;
}

namespace {

using Kind = TextureKind;

} // namespace

Image encode16(const Image& src, TextureKind kind, double jumpMax) {
  Image out(src.width(), src.height(), 4, PixelType::U16);
  const std::span<const float> s = src.values<float>();
  const std::span<std::uint16_t> d = out.values<std::uint16_t>();
  for (std::size_t i = 0; i < s.size(); i += 4) {
    switch (kind) {
    case Kind::Init:
      d[i + 0] = static_cast<std::uint16_t>(s[i + 0]);
      d[i + 1] = static_cast<std::uint16_t>(s[i + 1]);
      d[i + 2] = encodeUnit(s[i + 2]);
      d[i + 3] = static_cast<std::uint16_t>(s[i + 3] + 1.0f);
      break;
    case Kind::Jump:
      d[i + 0] = encodeJump(s[i + 0], jumpMax);
      d[i + 1] = encodeJump(s[i + 1], jumpMax);
      d[i + 2] = encodeUnit(s[i + 2]);
      d[i + 3] = encodeUnit(s[i + 3]);
      break;
    case Kind::Fold:
      for (int c = 0; c < 4; ++c) {
        d[i + c] = encodeUnit(s[i + c]);
      }
      break;
    }
  }
  return out;
}

namespace {

Image decode16(const Image& src, Kind kind, double jumpMax, const std::string& file) {
  if (src.channels() != 4 || src.type() != PixelType::U16) {
    fail("{}: expected a 16-bit RGBA PNG, got {} channels of {}", file, src.channels(),
         pixelTypeName(src.type()));
  }
  Image out(src.width(), src.height(), 4, PixelType::F32);
  const std::span<const std::uint16_t> s = src.values<std::uint16_t>();
  const std::span<float> d = out.values<float>();
  for (std::size_t i = 0; i < s.size(); i += 4) {
    switch (kind) {
    case Kind::Init:
      d[i + 0] = s[i + 0];
      d[i + 1] = s[i + 1];
      d[i + 2] = static_cast<float>(decodeUnit(s[i + 2]));
      d[i + 3] = static_cast<float>(s[i + 3]) - 1.0f;
      break;
    case Kind::Jump:
      d[i + 0] = static_cast<float>(decodeJump(s[i + 0], jumpMax));
      d[i + 1] = static_cast<float>(decodeJump(s[i + 1], jumpMax));
      d[i + 2] = static_cast<float>(decodeUnit(s[i + 2]));
      d[i + 3] = static_cast<float>(decodeUnit(s[i + 3]));
      break;
    case Kind::Fold:
      for (int c = 0; c < 4; ++c) {
        d[i + c] = static_cast<float>(decodeUnit(s[i + c]));
      }
      break;
    }
  }
  return out;
}

std::string layerName(const std::string& base, const char* stem, std::size_t layer, const std::string& ext) {
  return layer == 0 && std::string(stem) == "jump" ? base : fmt::format("{}{}{}", stem, layer, ext);
}

} // namespace

void saveTextures(const std::filesystem::path& dir, const Project& project, const Textures& tex) {
  const bool exr = project.outputs.encoding == Outputs::Encoding::Exr;
  const std::string ext = exr ? ".exr" : ".png";
  const double jumpMax = std::max(tex.jumpMax(), 1e-6);
  auto write = [&](const std::string& name, const Image& image, Kind kind) {
    if (exr) {
      Image raw = image;
      if (kind == Kind::Init) {
        std::span<float> v = raw.values<float>();
        for (std::size_t i = 3; i < v.size(); i += 4) {
          v[i] += 1.0f; // profile k + 1, 0 = still: the same numbers as the PNG
        }
      }
      saveImage(dir / name, raw);
    } else {
      saveImage(dir / name, encode16(image, kind, jumpMax));
    }
  };
  saveImage(dir / project.outputs.color, tex.atlas.color);
  write(project.outputs.init, tex.init, Kind::Init);
  nlohmann::json jumps = nlohmann::json::array();
  nlohmann::json folds = nlohmann::json::array();
  for (std::size_t l = 0; l < tex.jump.size(); ++l) {
    const std::string name = layerName(project.outputs.jump, "jump", l, ext);
    write(name, tex.jump[l], Kind::Jump);
    jumps.push_back(name);
  }
  for (std::size_t l = 0; l < tex.fold.size(); ++l) {
    const std::string name = fmt::format("fold{}{}", l, ext);
    write(name, tex.fold[l], Kind::Fold);
    folds.push_back(name);
  }
  nlohmann::json images = nlohmann::json::array();
  for (const AtlasEntry& e : tex.atlas.entries) {
    images.push_back({{"id", e.id},
                      {"image_size", {e.imageSize.x, e.imageSize.y}},
                      {"crop", {e.crop.min.x, e.crop.min.y, e.crop.width(), e.crop.height()}},
                      {"atlas", {e.atlasPos.x, e.atlasPos.y}}});
  }
  const nlohmann::json project_ = toJson(project);
  nlohmann::json meta = {
      {"format", "sylva-fold-textures"},
      {"version", 1},
      {"encoding", exr ? "exr" : "rgba16"},
      {"size", {tex.width(), tex.height()}},
      {"jump_max_px", jumpMax},
      {"jump_layers", project.jumpLayers},
      {"files",
       {{"color", project.outputs.color}, {"init", project.outputs.init}, {"jump", jumps}, {"fold", folds}}},
      {"canvas", project.images[static_cast<std::size_t>(project.canvasIndex())].id},
      {"images", images},
      {"profiles", project_["profiles"]}};
  saveJsonFile(dir / "folding.json", meta);
}

Textures loadTextures(const std::filesystem::path& dir, std::vector<Profile>* profiles,
                      std::vector<double>* jumpLayers) {
  const std::filesystem::path metaPath = dir / "folding.json";
  const nlohmann::json meta = loadJsonFile(metaPath);
  requireJsonVersion(meta, 1, metaPath.string());
  Textures tex;
  try {
    const bool exr = meta.at("encoding").get<std::string>() == "exr";
    const double jumpMax = meta.at("jump_max_px").get<double>();
    const auto& files = meta.at("files");
    auto read = [&](const std::string& name, Kind kind) {
      const std::filesystem::path path = dir / name;
      Image image = loadImage(path);
      if (exr) {
        if (kind == Kind::Init) {
          std::span<float> v = image.values<float>();
          for (std::size_t i = 3; i < v.size(); i += 4) {
            v[i] -= 1.0f;
          }
        }
        return image;
      }
      return decode16(image, kind, jumpMax, path.string());
    };
    tex.atlas.color = loadImage(dir / files.at("color").get<std::string>());
    tex.init = read(files.at("init").get<std::string>(), Kind::Init);
    for (const auto& name : files.at("jump")) {
      tex.jump.push_back(read(name.get<std::string>(), Kind::Jump));
    }
    for (const auto& name : files.at("fold")) {
      tex.fold.push_back(read(name.get<std::string>(), Kind::Fold));
    }
    for (const auto& e : meta.at("images")) {
      AtlasEntry entry;
      entry.id = e.at("id").get<std::string>();
      entry.imageSize = {e.at("image_size")[0].get<int>(), e.at("image_size")[1].get<int>()};
      entry.crop.min = {e.at("crop")[0].get<int>(), e.at("crop")[1].get<int>()};
      entry.crop.max = entry.crop.min + glm::ivec2(e.at("crop")[2].get<int>(), e.at("crop")[3].get<int>());
      entry.atlasPos = {e.at("atlas")[0].get<int>(), e.at("atlas")[1].get<int>()};
      tex.atlas.entries.push_back(entry);
    }
    if (profiles || jumpLayers) {
      nlohmann::json fake = {{"format", "sylva-fold"},
                             {"version", 1},
                             {"atlas", {{"images", {{{"id", "x"}, {"file", "x.png"}}}}}},
                             {"jump_layers", meta.at("jump_layers")},
                             {"profiles", meta.at("profiles")},
                             {"zones", nlohmann::json::array()}};
      const Project p = parseProject(fake, metaPath.string());
      if (profiles) {
        *profiles = p.profiles;
      }
      if (jumpLayers) {
        *jumpLayers = p.jumpLayers;
      }
    }
  } catch (const nlohmann::json::exception& e) {
    fail("{}: {}", metaPath.string(), e.what());
  }
  const glm::ivec2 size(tex.init.width(), tex.init.height());
  auto same = [&](const Image& image) { return image.width() == size.x && image.height() == size.y; };
  if (!same(tex.atlas.color) || !std::all_of(tex.jump.begin(), tex.jump.end(), same) ||
      !std::all_of(tex.fold.begin(), tex.fold.end(), same)) {
    fail("{}: the textures differ in size", metaPath.string());
  }
  tex.atlas.color = toRgba8(tex.atlas.color);
  return tex;
}

// ---------------------------------------------------------------------------------------------------------
// Pictures

namespace {

Image greyBackdrop(const Image& color) {
  Image out(color.width(), color.height(), 4, PixelType::U8);
  const auto* s = reinterpret_cast<const std::uint8_t*>(color.data());
  auto* d = reinterpret_cast<std::uint8_t*>(out.data());
  for (std::size_t i = 0; i < static_cast<std::size_t>(color.width()) * color.height(); ++i) {
    const auto g =
        static_cast<std::uint8_t>((s[i * 4] * 77 + s[i * 4 + 1] * 150 + s[i * 4 + 2] * 29) / 256 / 2 + 64);
    d[i * 4] = d[i * 4 + 1] = d[i * 4 + 2] = g;
    d[i * 4 + 3] = 255;
  }
  return out;
}

void plot(Image& img, int x, int y, glm::u8vec3 c) {
  if (x < 0 || y < 0 || x >= img.width() || y >= img.height()) {
    return;
  }
  auto* d = reinterpret_cast<std::uint8_t*>(img.data()) + (static_cast<std::size_t>(y) * img.width() + x) * 4;
  d[0] = c.r;
  d[1] = c.g;
  d[2] = c.b;
  d[3] = 255;
}

void line(Image& img, glm::vec2 a, glm::vec2 b, glm::u8vec3 c) {
  const int steps = std::max(1, static_cast<int>(std::ceil(glm::length(b - a))));
  for (int i = 0; i <= steps; ++i) {
    const glm::vec2 p = glm::mix(a, b, static_cast<float>(i) / steps);
    plot(img, static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)), c);
  }
}

} // namespace

Image vectorFieldPicture(const Textures& tex, int step, int layer) {
  Image out = greyBackdrop(tex.atlas.color);
  const int w = tex.width();
  const std::span<const float> init = tex.init.values<float>();
  const std::span<const float> jump = tex.jump.at(static_cast<std::size_t>(layer)).values<float>();
  step = std::max(2, step);
  for (int y = step / 2; y < tex.height(); y += step) {
    for (int x = step / 2; x < w; x += step) {
      const std::size_t i = (static_cast<std::size_t>(y) * w + x) * 4;
      if (init[i + 3] < 0.0f) {
        continue;
      }
      // Forward motion (what the viewer sees move): from the read point to the texel, i.e. −J.
      const glm::vec2 j(jump[i], jump[i + 1]);
      const glm::vec2 tip(x + 0.5f, y + 0.5f);
      const glm::vec2 tail = tip + j;
      const bool still = glm::length(j) < 0.5f;
      const glm::u8vec3 colour = still ? glm::u8vec3(40, 160, 255) : glm::u8vec3(255, 220, 40);
      if (still) {
        plot(out, x, y, colour);
        continue;
      }
      line(out, tail, tip, colour);
      const glm::vec2 dir = glm::normalize(tip - tail);
      const glm::vec2 side(-dir.y, dir.x);
      const float head = std::min(4.0f, 0.4f * glm::length(j));
      line(out, tip, tip - head * dir + 0.6f * head * side, colour);
      line(out, tip, tip - head * dir - 0.6f * head * side, colour);
      plot(out, x, y, glm::u8vec3(255, 60, 40));
    }
  }
  return out;
}

Image thresholdHeatMap(const Textures& tex, int which, int layer) {
  Image out = greyBackdrop(tex.atlas.color);
  const std::span<const float> init = tex.init.values<float>();
  const std::span<const float> jump = tex.jump.at(static_cast<std::size_t>(layer)).values<float>();
  auto* d = reinterpret_cast<std::uint8_t*>(out.data());
  for (std::size_t i = 0; i < init.size() / 4; ++i) {
    if (init[i * 4 + 3] < 0.0f) {
      continue;
    }
    const float t = std::clamp(jump[i * 4 + 2 + (which ? 1 : 0)], 0.0f, 1.0f);
    // Blue (t = 0) through green to red (t = 1); texels that never move (t0 = t1) stay grey.
    if (jump[i * 4 + 2] >= jump[i * 4 + 3]) {
      continue;
    }
    d[i * 4 + 0] = static_cast<std::uint8_t>(255.0f * std::clamp(2.0f * t - 0.5f, 0.0f, 1.0f));
    d[i * 4 + 1] = static_cast<std::uint8_t>(255.0f * (1.0f - std::abs(2.0f * t - 1.0f)));
    d[i * 4 + 2] = static_cast<std::uint8_t>(255.0f * std::clamp(1.5f - 2.0f * t, 0.0f, 1.0f));
  }
  return out;
}

} // namespace sylva::folding
