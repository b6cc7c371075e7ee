#include "amos/segmentation/nanodet_import_dnn.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/shape_utils.hpp>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

// Number of innermost axes that `order` leaves in place.
int keptInnerAxes(const std::vector<int>& order) {
  const int n = static_cast<int>(order.size());
  int k = 0;
  while (k < n && order[static_cast<std::size_t>(n - 1 - k)] == n - 1 - k) ++k;
  return k;
}

bool isPermutation(const std::vector<int>& order) {
  std::vector<bool> seen(order.size(), false);
  for (int axis : order) {
    if (axis < 0 || axis >= static_cast<int>(order.size()) || seen[static_cast<std::size_t>(axis)]) return false;
    seen[static_cast<std::size_t>(axis)] = true;
  }
  return true;
}

// out = in with its axes permuted by order (output axis i = input axis order[i]); both dense CV_32F. The innermost
// axes that stay in place form one contiguous block, copied at once; the outer output index runs in row-major order
// while the input offset follows it through the input strides.
void transposeInto(const cv::Mat& in, const std::vector<int>& order, cv::Mat& out) {
  const int n = in.dims;
  const int kept = keptInnerAxes(order);
  const int outer = n - kept;
  std::size_t block = 1;
  for (int a = outer; a < n; ++a) block *= static_cast<std::size_t>(in.size[a]);
  std::vector<std::size_t> in_stride(static_cast<std::size_t>(n), 1);
  for (int a = n - 2; a >= 0; --a) in_stride[a] = in_stride[a + 1] * static_cast<std::size_t>(in.size[a + 1]);
  std::vector<int> out_size(static_cast<std::size_t>(outer)), index(static_cast<std::size_t>(outer), 0);
  std::size_t blocks = 1;
  for (int a = 0; a < outer; ++a) {
    out_size[a] = in.size[order[a]];
    blocks *= static_cast<std::size_t>(out_size[a]);
  }
  const float* src = in.ptr<float>();
  float* dst = out.ptr<float>();
  std::size_t offset = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    std::memcpy(dst + b * block, src + offset, block * sizeof(float));
    for (int a = outer - 1; a >= 0; --a) {
      const std::size_t stride = in_stride[static_cast<std::size_t>(order[a])];
      offset += stride;
      if (++index[a] < out_size[a]) break;
      offset -= stride * static_cast<std::size_t>(out_size[a]);
      index[a] = 0;
    }
  }
}

cv::dnn::MatShape permutedShape(const cv::dnn::MatShape& shape, const std::vector<int>& order) {
  cv::dnn::MatShape out(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) out[i] = shape[static_cast<std::size_t>(order[i])];
  return out;
}

// The block-copy transpose as a dnn layer (see the header).
class BlockTransposeLayer : public cv::dnn::Layer {
 public:
  BlockTransposeLayer(const cv::dnn::LayerParams& params, std::vector<int> order)
      : cv::dnn::Layer(params), order_(std::move(order)) {}

  bool getMemoryShapes(const std::vector<cv::dnn::MatShape>& inputs, const int /*requiredOutputs*/,
                       std::vector<cv::dnn::MatShape>& outputs,
                       std::vector<cv::dnn::MatShape>& /*internals*/) const override {
    CV_Assert(inputs.size() == 1 && inputs[0].size() == order_.size());
    outputs.assign(1, permutedShape(inputs[0], order_));
    return false;
  }

  void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
               cv::OutputArrayOfArrays /*internals*/) override {
    std::vector<cv::Mat> inputs, outputs;
    inputs_arr.getMatVector(inputs);
    outputs_arr.getMatVector(outputs);
    CV_Assert(inputs.size() == 1 && outputs.size() == 1 && inputs[0].type() == CV_32F &&
              outputs[0].type() == CV_32F && inputs[0].isContinuous() && outputs[0].isContinuous());
    transposeInto(inputs[0], order_, outputs[0]);
  }

 private:
  std::vector<int> order_;
};

// What the constructors below need from the import in progress; set only by the importing thread.
struct ImportContext {
  double resize_x = 1.0, resize_y = 1.0;  // input size / export size
};
thread_local const ImportContext* t_import = nullptr;

std::vector<int> orderParam(const cv::dnn::LayerParams& params) {
  std::vector<int> order;
  if (!params.has("order")) return order;
  const cv::dnn::DictValue& value = params.get("order");
  for (int i = 0; i < value.size(); ++i) order.push_back(value.get<int>(i));
  return order;
}

cv::Ptr<cv::dnn::Layer> makeTranspose(cv::dnn::LayerParams& params) {
  if (t_import != nullptr) {
    std::vector<int> order = orderParam(params);
    if (order.size() >= 2 && isPermutation(order) && keptInnerAxes(order) > 0)
      return cv::makePtr<BlockTransposeLayer>(params, std::move(order));
  }
  return cv::dnn::PermuteLayer::create(params);
}

cv::Ptr<cv::dnn::Layer> makeResize(cv::dnn::LayerParams& params) {
  if (t_import != nullptr && params.has("height") && params.has("width")) {
    params.set("height", static_cast<int>(std::lround(params.get<int>("height") * t_import->resize_y)));
    params.set("width", static_cast<int>(std::lround(params.get<int>("width") * t_import->resize_x)));
  }
  return cv::dnn::ResizeLayer::create(params);
}

// Our constructors stacked over OpenCV's for the lifetime of the object, one import at a time process-wide.
class ScopedImportLayers {
 public:
  explicit ScopedImportLayers(const ImportContext& context) : lock_(mutex()) {
    cv::dnn::LayerFactory::registerLayer("Permute", makeTranspose);
    cv::dnn::LayerFactory::registerLayer("Resize", makeResize);
    t_import = &context;
  }
  ~ScopedImportLayers() {
    t_import = nullptr;
    cv::dnn::LayerFactory::unregisterLayer("Resize");
    cv::dnn::LayerFactory::unregisterLayer("Permute");
  }
  ScopedImportLayers(const ScopedImportLayers&) = delete;
  ScopedImportLayers& operator=(const ScopedImportLayers&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
};

}  // namespace

cv::Mat transposeBlob(const cv::Mat& input, const std::vector<int>& order) {
  core::require(input.type() == CV_32F && input.isContinuous() && static_cast<int>(order.size()) == input.dims &&
                    isPermutation(order),
                "transposeBlob: needs a dense CV_32F blob and a permutation of its axes");
  const cv::dnn::MatShape shape = permutedShape(cv::dnn::shape(input), order);
  cv::Mat out(static_cast<int>(shape.size()), shape.data(), CV_32F);
  transposeInto(input, order, out);
  return out;
}

NanoDetImport loadNanoDet(const std::string& path, int export_side, cv::Size input_size) {
  core::require(export_side > 0 && input_size.width % 32 == 0 && input_size.height % 32 == 0 &&
                    input_size.width > 0 && input_size.height > 0,
                fmt::format("NanoDet input {}x{} must be positive multiples of 32", input_size.width,
                            input_size.height));
  NanoDetImport result;
  result.input_size = input_size;
  const ImportContext context{static_cast<double>(input_size.width) / export_side,
                              static_cast<double>(input_size.height) / export_side};
  try {
    const ScopedImportLayers layers(context);
    result.net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw core::Error(fmt::format("cannot load segmentation model {}: not an ONNX network OpenCV {} can read "
                                  "(corrupt or truncated file?): {}",
                                  path, CV_VERSION, e.what()));
  }
  core::require(!result.net.empty(), fmt::format("cannot load segmentation model {}: empty network", path));
  result.net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  result.net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  for (const std::string& name : result.net.getLayerNames()) {
    const cv::Ptr<cv::dnn::Layer> layer = result.net.getLayer(result.net.getLayerId(name));
    if (layer.dynamicCast<BlockTransposeLayer>()) ++result.block_transposes;
    const auto reshape = layer.dynamicCast<cv::dnn::ReshapeLayer>();
    if (!reshape || input_size == cv::Size(export_side, export_side)) continue;
    // [.., s, s] with s = export_side / stride for one of NanoDet's strides: the spatial part of a shuffle Reshape.
    cv::dnn::MatShape& shape = reshape->newShapeDesc;
    const std::size_t n = shape.size();
    if (n < 4 || shape[n - 1] != shape[n - 2] || shape[n - 1] <= 0 || export_side % shape[n - 1] != 0) continue;
    const int stride = export_side / shape[n - 1];
    if (stride != 8 && stride != 16 && stride != 32) continue;
    shape[n - 2] = input_size.height / stride;
    shape[n - 1] = input_size.width / stride;
    ++result.reshapes_adapted;
  }
  return result;
}

}  // namespace amos::segmentation
