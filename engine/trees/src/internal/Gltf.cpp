#include "internal/Gltf.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <fstream>

namespace sylva::trees::internal {

void appendBytes(std::vector<std::uint8_t>& buffer, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  buffer.insert(buffer.end(), bytes, bytes + size);
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

nlohmann::json matrixJson(const glm::mat4& m) {
  nlohmann::json out = nlohmann::json::array();
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      out.push_back(m[c][r]);
    }
  }
  return out;
}

std::size_t GltfBuffer::addView(const void* data, std::size_t size, std::optional<int> target) {
  while (bytes.size() % 4 != 0) {
    bytes.push_back(0);
  }
  const std::size_t offset = bytes.size();
  appendBytes(bytes, data, size);
  nlohmann::json view{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
  if (target) {
    view["target"] = *target;
  }
  views.push_back(view);
  return views.size() - 1;
}

std::size_t GltfBuffer::addAccessor(std::size_t view, int componentType, std::size_t count,
                                    const char* type) {
  accessors.push_back(
      {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
  return accessors.size() - 1;
}

std::size_t writeGltf(const std::filesystem::path& path, nlohmann::json gltf,
                      const std::vector<std::uint8_t>& buffer, bool binary) {
  if (!binary) {
    gltf["buffers"] = nlohmann::json::array(
        {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}});
    const std::string text = gltf.dump(1) + "\n";
    writeTextFile(path, text);
    return text.size();
  }
  gltf["buffers"] = nlohmann::json::array({{{"byteLength", buffer.size()}}});
  std::string json = gltf.dump();
  while (json.size() % 4 != 0) {
    json += ' ';
  }
  const std::size_t binLength = (buffer.size() + 3) / 4 * 4;
  const std::size_t total = 12 + 8 + json.size() + (buffer.empty() ? 0 : 8 + binLength);
  if (total > 0xffffffffu) {
    fail("{}: too large for a .glb file ({} bytes)", path.string(), total);
  }
  std::vector<std::uint8_t> out;
  out.reserve(total);
  auto u32 = [&](std::uint32_t v) { appendBytes(out, &v, 4); };
  u32(0x46546C67u); // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(total));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534Au); // "JSON"
  appendBytes(out, json.data(), json.size());
  if (!buffer.empty()) {
    u32(static_cast<std::uint32_t>(binLength));
    u32(0x004E4942u); // "BIN\0"
    appendBytes(out, buffer.data(), buffer.size());
    out.resize(total, 0);
  }
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream file(tmp, std::ios::binary);
    file.write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
    file.close();
    if (!file) {
      fail("{}: write failed", path.string());
    }
  });
  return out.size();
}

} // namespace sylva::trees::internal
