#pragma once

#include <sylva/core/Image.hpp>

#include <filesystem>
#include <span>
#include <string>

namespace sylva::media {

/**
 * Writes an animated GIF89a of `frames` (RGBA8, all the same size; alpha is ignored). Every frame has a
 * palette of its own (at most 256 colours, a variance-based median cut; docs/folding.md "Exports"): the first
 * frame's is the global colour map; each later frame stores only the rectangle of pixels that changed since
 * the previous frame (disposal "do not dispose"), with a local colour map quantised from that rectangle, so
 * still parts of a cinemagraph keep their pixels and do not shimmer. With `dither` (the default) the pixels
 * are mapped by Floyd–Steinberg error diffusion (serpentine), so smooth tones (skin, sky) keep their local
 * mean instead of posterising into bands; without it every pixel takes its nearest palette colour.
 * Deterministic: the same frames give a byte-identical file. `delayCs` is the delay of each frame in
 * hundredths of a second (1..65535); `loop` adds the NETSCAPE2.0 "loop forever" block. Written to a temporary
 * file and renamed. Throws sylva::Error naming the file (no frames, sizes that differ, giflib errors).
 */
void writeGif(const std::filesystem::path& path, std::span<const Image> frames, int delayCs, bool loop = true,
              bool dither = true);

/**
 * Writes a sprite sheet: `frames` (RGBA8, all the same size w×h) laid out row by row in `columns` columns
 * (fewer when there are fewer frames) into one PNG at `imagePath`, and `jsonPath` describing it:
 * {"format":"sylva-fold-sprites","version":1,"image":FILE_NAME,"size":[W,H],"columns","rows","fps",
 *  "frames":[{"index","x","y","w","h","t"}]} with rectangles in sheet pixels (top-left origin) and t the
 * frame's time in seconds (index / fps). Both files are written atomically. Throws sylva::Error naming the
 * file (no frames, sizes that differ, a sheet wider or taller than 65536 pixels).
 */
void writeSpriteSheet(const std::filesystem::path& imagePath, const std::filesystem::path& jsonPath,
                      std::span<const Image> frames, int columns, double fps);

/** True when an executable `ffmpeg` is on PATH. */
bool ffmpegAvailable();

/**
 * Encodes `frames` (RGBA8, same size) at `fps` frames per second into a video by piping raw RGBA frames to
 * the `ffmpeg` program found on PATH: `.mp4` with libx264 (yuv420p, CRF 18), `.webm` with libvpx-vp9
 * (CRF 30); odd sizes are padded to even. ffmpeg writes a temporary file next to `path`, renamed when it
 * succeeds. Throws sylva::Error: "ffmpeg not found on PATH: install it (apt install ffmpeg) or write
 * --gif/--sprites/--frames instead" when it is absent, or one line with ffmpeg's exit status and the last
 * line it printed when it fails (nothing is left at `path` then).
 */
void writeVideo(const std::filesystem::path& path, std::span<const Image> frames, double fps);

} // namespace sylva::media
