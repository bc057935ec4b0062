#include <sylva/texsynth/Quilt.hpp>

#include "internal/Candidates.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/texsynth/MinCut.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sylva::texsynth {

int QuiltSettings::effectiveOverlap() const {
  return overlap > 0 ? overlap : std::max(1, block / 6);
}

void validate(const QuiltSettings& settings, const Texture& source) {
  if (settings.block < 4 || settings.block > 1024) {
    fail("block: {} is out of range [4, 1024]", settings.block);
  }
  if (settings.overlap < 0 || settings.effectiveOverlap() > settings.block / 2) {
    fail("overlap: {} is out of range [0, {}] (at most half the block)", settings.overlap,
         settings.block / 2);
  }
  if (!std::isfinite(settings.tolerance) || settings.tolerance < 0.0 || settings.tolerance > 10.0) {
    fail("tolerance: {} is not a finite number in [0, 10]", settings.tolerance);
  }
  if (settings.maxCandidates < 16 || settings.maxCandidates > 1000000) {
    fail("maxCandidates: {} is out of range [16, 1000000]", settings.maxCandidates);
  }
  if (source.empty()) {
    fail("{}: the source image is empty", source.name);
  }
  if (source.width < settings.block || source.height < settings.block) {
    fail("{}: the image is {}x{}, smaller than the {}x{} block", source.name, source.width, source.height,
         settings.block, settings.block);
  }
}

int quiltBlockCount(int outWidth, int outHeight, const QuiltSettings& settings) {
  const int overlap = settings.effectiveOverlap();
  const int step = std::max(1, settings.block - overlap);
  return std::max(1, (outWidth - overlap + step - 1) / step) *
         std::max(1, (outHeight - overlap + step - 1) / step);
}

Texture quilt(const Texture& source, int outWidth, int outHeight, const QuiltSettings& settings,
              Progress* progress) {
  validate(settings, source);
  if (outWidth < 1 || outHeight < 1 || outWidth > kMaxTextureSide || outHeight > kMaxTextureSide) {
    fail("size: {}x{} is out of range (1..{} per side)", outWidth, outHeight, kMaxTextureSide);
  }
  const int block = settings.block;
  const int overlap = settings.effectiveOverlap();
  const int step = block - overlap;
  const int blocksX = std::max(1, (outWidth - overlap + step - 1) / step);
  const int blocksY = std::max(1, (outHeight - overlap + step - 1) / step);
  const int channels = source.channels;
  // The canvas holds whole blocks; the output is its lower-left corner.
  Texture canvas = Texture::blank(blocksX * step + overlap, blocksY * step + overlap, channels, "quilt");
  const std::vector<detail::Position> candidates =
      detail::candidateGrid(source.width, source.height, block, block, settings.maxCandidates);
  Rng rng(settings.seed, 0x5175696c74ULL);
  std::vector<double> errors(candidates.size());

  for (int by = 0; by < blocksY; ++by) {
    for (int bx = 0; bx < blocksX; ++bx) {
      if (progress != nullptr && progress->cancelled()) {
        fail("quilting cancelled");
      }
      const int px = bx * step;
      const int py = by * step;
      const int left = bx > 0 ? overlap : 0;
      const int low = by > 0 ? overlap : 0;
      // Texels of the block that overlap what is already placed: the L-shaped union of both strips.
      const auto inOverlap = [&](int x, int y) { return x < left || y < low; };
      std::vector<detail::Position> overlapTexels;
      for (int y = 0; y < block; ++y) {
        for (int x = 0; x < block; ++x) {
          if (inOverlap(x, y)) {
            overlapTexels.push_back({x, y});
          }
        }
      }
      std::size_t chosen = 0;
      if (left == 0 && low == 0) {
        chosen = rng.below(static_cast<std::uint32_t>(candidates.size()));
      } else {
        parallelFor(
            candidates.size(),
            [&](std::size_t begin, std::size_t end) {
              for (std::size_t i = begin; i < end; ++i) {
                double sum = 0.0;
                for (const detail::Position& t : overlapTexels) {
                  sum += detail::colourError(canvas.at(px + t.x, py + t.y),
                                             source.at(candidates[i].x + t.x, candidates[i].y + t.y));
                }
                errors[i] = sum;
              }
            },
            16);
        chosen = chooseCandidate(errors, settings.tolerance, rng);
      }
      const detail::Position from = candidates[chosen];
      std::vector<std::uint8_t> keepOld(static_cast<std::size_t>(block) * block, 0);
      if (left > 0 || low > 0) {
        ErrorSurface surface{block, block, std::vector<double>(static_cast<std::size_t>(block) * block, 0.0)};
        for (int y = 0; y < block; ++y) {
          for (int x = 0; x < block; ++x) {
            if (inOverlap(x, y)) {
              surface.values[static_cast<std::size_t>(y) * block + x] =
                  detail::colourError(canvas.at(px + x, py + y), source.at(from.x + x, from.y + y));
            }
          }
        }
        keepOld = overlapMask(surface, left, low);
      }
      for (int y = 0; y < block; ++y) {
        for (int x = 0; x < block; ++x) {
          if (keepOld[static_cast<std::size_t>(y) * block + x] == 0) {
            std::memcpy(canvas.at(px + x, py + y), source.at(from.x + x, from.y + y),
                        sizeof(float) * static_cast<std::size_t>(channels));
          }
        }
      }
      if (progress != nullptr) {
        progress->advance();
      }
    }
  }
  Texture out = Texture::blank(outWidth, outHeight, channels, "quilt");
  for (int y = 0; y < outHeight; ++y) {
    std::memcpy(out.at(0, y), canvas.at(0, y), sizeof(float) * static_cast<std::size_t>(outWidth) * channels);
  }
  return out;
}

} // namespace sylva::texsynth
