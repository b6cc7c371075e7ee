#pragma once
// Output files that are never seen half-written: the bytes go to a temporary file in the same folder
// ("<name>.partial"), which is then renamed over the final name. A rename within one file system is atomic, so a
// run killed at any moment leaves either the previous file, the complete new one, or no file at all; a failed
// write removes the temporary file and leaves any earlier file under the final name untouched.
#include <opencv2/core.hpp>

#include <string>
#include <string_view>

namespace amos::io {

// The temporary name a file is written under before the rename: "<path>.partial".
std::string partialPath(const std::string& path);

// Writes `bytes` to `path` as described above. Throws core::Error naming the file when it cannot be written.
void writeFileAtomically(const std::string& path, std::string_view bytes);

// Encodes `image` in the format its extension names (io::encodeImage: .png, .jpg, .pgm, ...) and writes it atomically.
void writeImageAtomically(const std::string& path, const cv::Mat& image);

}  // namespace amos::io
