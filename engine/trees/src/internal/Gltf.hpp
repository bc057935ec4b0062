#pragma once
// glTF writing shared by the piece export (Import.cpp) and the tree export (Export.cpp): one binary buffer
// with its views and accessors, and the file written as .gltf (buffer embedded as base64) or .glb.

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sylva::trees::internal {

constexpr int kGltfFloat = 5126;
constexpr int kGltfUnsignedByte = 5121;
constexpr int kGltfUnsignedShort = 5123;
constexpr int kGltfUnsignedInt = 5125;
constexpr int kGltfArrayBuffer = 34962;
constexpr int kGltfElementArrayBuffer = 34963;

void appendBytes(std::vector<std::uint8_t>& buffer, const void* data, std::size_t size);
std::string base64(const std::vector<std::uint8_t>& bytes);
/** A matrix as glTF's 16 numbers, column major. */
nlohmann::json matrixJson(const glm::mat4& m);

/** The buffer of a glTF file being built: bytes, bufferViews and accessors. */
struct GltfBuffer {
  std::vector<std::uint8_t> bytes;
  nlohmann::json views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();

  /** Appends `size` bytes as a new buffer view (4-byte aligned); returns its index. */
  std::size_t addView(const void* data, std::size_t size, std::optional<int> target);
  /** An accessor of `count` elements on `view`; returns its index. */
  std::size_t addAccessor(std::size_t view, int componentType, std::size_t count, const char* type);
};

/**
 * Writes `gltf` with `buffer` as its buffer 0 (set here) atomically: a .glb file (JSON and BIN chunks) when
 * `binary`, else JSON text with the buffer as a base64 data URI. Returns the bytes written. Throws
 * sylva::Error naming the file.
 */
std::size_t writeGltf(const std::filesystem::path& path, nlohmann::json gltf,
                      const std::vector<std::uint8_t>& buffer, bool binary);

} // namespace sylva::trees::internal
