#pragma once
// What an image file says about its size before any pixel is decoded, so that a loader handing a file to a
// third-party decoder (OpenCV) can refuse a small file that claims a huge image: a 2.6 KB progressive JPEG
// claiming 20000×20000 pixels makes libjpeg allocate and zero about 2 GB of coefficients before reading a
// scan.

#include <filesystem>
#include <optional>
#include <string>

namespace sylva {

/** An image file's format and size, as its header states them (nothing decoded, nothing verified). */
struct ImageHeader {
  std::string format; ///< "PNG", "JPEG", "WebP", "TIFF", "BMP", "OpenEXR", "PNM", "PAM", "PFM",
                      ///< "Sun raster", "Radiance HDR" or "JPEG 2000"
  int width = 0;      ///< pixels, as stated (may be 0 in a damaged file)
  int height = 0;     ///< pixels, as stated
};

/**
 * Reads the header of an image file (the formats below), recognised by its content (the extension
 * is only a name): PNG's IHDR, the first JPEG frame header (SOF0–SOF15, skipping every segment before it,
 * however long), WebP's VP8, VP8L or VP8X chunk, the first TIFF directory's ImageWidth and ImageLength
 * (either byte order; not BigTIFF), a BMP's core or info header (|height| for top-down bitmaps), the first
 * OpenEXR header's dataWindow; the width and height tokens of PBM/PGM/PPM (P1–P6) and PFM (PF, Pf), PAM's
 * WIDTH and HEIGHT lines, a Sun raster's header, a Radiance HDR's resolution line, a JPEG 2000 codestream's
 * SIZ segment (bare, or in a JP2 file's codestream box). These are every format OpenCV's image readers take
 * apart from DICOM. nullopt for any other format or a header cut short before the size. Reads only the bytes
 * up to the size fields. Throws sylva::Error naming the file when it cannot be opened.
 */
std::optional<ImageHeader> readImageHeader(const std::filesystem::path& path);

} // namespace sylva
