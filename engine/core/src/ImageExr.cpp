#include <sylva/core/Image.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cstdint>
#include <exception>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace sylva {

namespace {

/** Channel names in our interleaved order for 1..4 channels. */
std::vector<std::string> namesFor(int channels) {
  switch (channels) {
  case 1:
    return {"Y"};
  case 2:
    return {"Y", "A"};
  case 3:
    return {"R", "G", "B"};
  default:
    return {"R", "G", "B", "A"};
  }
}

} // namespace

Image loadExr(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    fail("{}: cannot open file (missing)", path.string());
  }
  // OpenEXR sizes its line buffers and decompressors from the header while opening the file, before we see
  // it: a 300-byte header once asked for 2 GB (found by fuzzing). Its own sanity check then refuses images
  // and tiles larger than our Image accepts (65536 per side).
  static std::once_flag limits;
  std::call_once(limits, [] {
    Imf::Header::setMaxImageSize(65536, 65536);
    Imf::Header::setMaxTileSize(65536, 65536);
  });
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    // In 64 bits: a corrupt header's window can span more than an int.
    const long long wideWidth = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long wideHeight = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (wideWidth <= 0 || wideHeight <= 0 || wideWidth > 65536 || wideHeight > 65536) {
      fail("{}: EXR data window {}x{} is out of range (1..65536 per side)", path.string(), wideWidth,
           wideHeight);
    }
    const int width = static_cast<int>(wideWidth);
    const int height = static_cast<int>(wideHeight);
    const Imf::ChannelList& list = file.header().channels();
    std::vector<std::string> names;
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
      names = {"R", "G", "B"};
    } else if (list.findChannel("Y")) {
      names = {"Y"};
    } else if (list.begin() != list.end()) {
      names = {list.begin().name()};
    } else {
      fail("{}: EXR file has no channels", path.string());
    }
    if (list.findChannel("A")) {
      names.push_back("A");
    }
    // OpenEXR's codecs (ZIP, PIZ, RLE, B44, DWA) shrink data by far less than 4096:1 (ZIP, the best on flat
    // images, ~1032:1 on 16-bit halves read back as 32-bit floats); a header claiming more pixels than the
    // file can hold is corrupt and is rejected before anything is allocated.
    const double claimed = static_cast<double>(width) * height * static_cast<double>(names.size()) * 4.0;
    const auto fileSize = static_cast<double>(std::filesystem::file_size(path));
    if (claimed > fileSize * 4096.0 + 1e6) {
      fail("{}: truncated or corrupt EXR: data window {}x{} with {} channels cannot fit in {} bytes",
           path.string(), width, height, names.size(), static_cast<std::uintmax_t>(fileSize));
    }
    Image image(width, height, static_cast<int>(names.size()), PixelType::F32);
    float* base = image.values<float>().data();
    const std::size_t xStride = sizeof(float) * names.size();
    const std::size_t yStride = xStride * static_cast<std::size_t>(width);
    // OpenEXR addresses the buffer with absolute data-window coordinates; Slice::Make offsets our pointer by
    // the window's origin in integer arithmetic (forming `base - min * stride` as a pointer overflows for
    // windows far from the origin, which fuzzing found).
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < names.size(); ++c) {
      frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, base + c, window, xStride, yStride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    fail("{}: cannot read EXR: {}", path.string(), e.what());
  }
}

void saveExr(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) {
    fail("{}: cannot save an empty image", path.string());
  }
  const Image floats = image.converted(PixelType::F32);
  const std::vector<std::string> names = namesFor(floats.channels());
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    try {
      Imf::Header header(floats.width(), floats.height());
      for (const std::string& name : names) {
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      }
      Imf::OutputFile file(tmp.c_str(), header);
      Imf::FrameBuffer frame;
      const std::size_t xStride = sizeof(float) * names.size();
      const char* base = reinterpret_cast<const char*>(floats.data());
      for (std::size_t c = 0; c < names.size(); ++c) {
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, const_cast<char*>(base) + c * sizeof(float), xStride,
                                          xStride * static_cast<std::size_t>(floats.width())));
      }
      file.setFrameBuffer(frame);
      file.writePixels(floats.height());
    } catch (const std::exception& e) {
      fail("{}: cannot write EXR: {}", path.string(), e.what());
    }
  });
}

} // namespace sylva
