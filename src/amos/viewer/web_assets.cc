#include "amos/viewer/web_assets.h"

#include <cstddef>

#include "amos/core/error.h"

namespace amos::viewer {

// Defined in the generated web_assets_data.cc.
extern const WebAsset kEmbeddedWebAssets[];
extern const std::size_t kEmbeddedWebAssetCount;

std::string_view mimeTypeOf(std::string_view name) {
  auto ends = [&](std::string_view ext) {
    return name.size() >= ext.size() && name.substr(name.size() - ext.size()) == ext;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".json")) return "application/json";
  if (ends(".png")) return "image/png";
  if (ends(".jpg") || ends(".jpeg")) return "image/jpeg";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".txt")) return "text/plain; charset=utf-8";
  if (ends(".ply")) return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

const WebAsset* findWebAsset(std::string_view name) {
  for (std::size_t i = 0; i < kEmbeddedWebAssetCount; ++i)
    if (kEmbeddedWebAssets[i].name == name) return &kEmbeddedWebAssets[i];
  return nullptr;
}

std::string_view webAssetText(std::string_view name) {
  const WebAsset* asset = findWebAsset(name);
  core::require(asset != nullptr, "viewer: the program has no embedded web file '" + std::string(name) + "'");
  return asset->content;
}

std::string threeJsDir() { return AMOS_THREE_JS_DIR; }

}  // namespace amos::viewer
