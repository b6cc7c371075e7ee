#pragma once
// The page's own files (src/amos/viewer/web/: index.html, viewer.js, viewer.css, report_template.html), embedded
// into the program at build time (embed_web_assets.cmake generates their data), so the binary needs no install
// step and serves the same page from the build tree as from anywhere. three.js is not embedded: it is Debian's
// libjs-three, read from its folder (threeJsDir()).
#include <string>
#include <string_view>

namespace amos::viewer {

struct WebAsset {
  std::string_view name;     // file name in web/
  std::string_view content;
  std::string_view mime;
};

// Null when there is no such file.
const WebAsset* findWebAsset(std::string_view name);
// Throws core::Error when there is no such file (a build error: the template is part of the program).
std::string_view webAssetText(std::string_view name);
// Content type of a file name by its extension ("application/octet-stream" when unknown).
std::string_view mimeTypeOf(std::string_view file_name);
// Folder of Debian's libjs-three (found at configure time): build/three.min.js, examples/js/controls/.
std::string threeJsDir();

}  // namespace amos::viewer
