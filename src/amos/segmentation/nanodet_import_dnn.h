#pragma once
// Loading a NanoDet-m ONNX export into OpenCV 4.6 dnn so that it runs fast and on any input shape (compiled only
// with AMOS_WITH_DNN).
//
// 1. Channel shuffle. Every ShuffleNetV2 block of NanoDet's backbone shuffles channels as Reshape [1, 2, C, h, w]
//    -> Transpose (0, 2, 1, 3, 4) -> Reshape. OpenCV 4.6 runs such a Transpose ("Permute") element by element
//    with index arithmetic: on a 2-core machine it was 28 of the 52 ms the 320x320 detector took. A transpose that
//    keeps the innermost axes in place only moves whole contiguous blocks (here h x w planes), so the layer
//    constructed for it here copies blocks (memcpy); transposes that move the innermost axis stay OpenCV's.
// 2. Input shape. The exports fix the spatial sizes of their square input S x S: the channel-shuffle Reshapes
//    ([1, 2, C, s, s], [1, -1, s, s] with s = S / stride) and the PAN's Resize layers (s x s). All scale with the
//    input, so the same weights run on W x H (multiples of 32) once each s x s becomes (H / stride) x (W / stride).
//
// Both changes need layer constructors of our own during the import. cv::dnn::LayerFactory takes plain function
// pointers and is process-wide, so they are registered (stacked on top of OpenCV's, which come back afterwards)
// only for the duration of loadNanoDet, one import at a time; the input scale reaches the Resize constructor
// through a thread_local set only by the importing thread, and every other use of the stacked constructors is
// exactly OpenCV's.
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include <string>
#include <vector>

namespace amos::segmentation {

struct NanoDetImport {
  cv::dnn::Net net;
  cv::Size input_size;           // what setInput must be given (width x height)
  int reshapes_adapted = 0;      // channel-shuffle Reshapes rewritten for a non-square input
  int block_transposes = 0;      // Transposes running as block copies
};

// Loads the export made for export_side x export_side (320 or 416) from `path` for an input of `input_size`
// (multiples of 32; export_side x export_side = the export's own shape). Throws core::Error naming the file when it
// is not an ONNX network OpenCV can read. Whether the network really is a NanoDet that runs on input_size shows
// only when it runs (the caller tests it once on a blank image).
NanoDetImport loadNanoDet(const std::string& path, int export_side, cv::Size input_size);

// The block-copy transpose on its own, for tests: permutes the axes of `input` (a dense CV_32F blob) by `order`
// (output axis i = input axis order[i]). Handles every order; it is a block copy when the order keeps the innermost
// axes in place.
cv::Mat transposeBlob(const cv::Mat& input, const std::vector<int>& order);

}  // namespace amos::segmentation
