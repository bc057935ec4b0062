#pragma once
// Reading a file through Assimp with the trees' one-line errors, shared by the piece importer (Import.cpp)
// and the leaf-cloud loader (Foliage.cpp).

#include <sylva/core/Error.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace sylva::trees::internal {

/**
 * Reads `file` with `importer` and post-processing `flags`; throws sylva::Error "<name>: …" when it is not a
 * regular file or Assimp cannot read it (Assimp's reason on one line). The scene belongs to `importer`.
 */
inline const aiScene* readScene(Assimp::Importer& importer, const std::filesystem::path& file,
                                const std::string& name, unsigned flags) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    fail("{}: {}", name, std::filesystem::exists(file, ec) ? "not a file" : "no such file");
  }
  const aiScene* scene = importer.ReadFile(file.string(), flags);
  if (scene == nullptr) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    std::replace(reason.begin(), reason.end(), '\r', ' ');
    fail("{}: cannot read the file: {}", name, reason.empty() ? std::string("unknown error") : reason);
  }
  return scene;
}

} // namespace sylva::trees::internal
