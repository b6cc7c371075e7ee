#include "amos/camera/openni2_source.h"

#include <OpenNI.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <exception>
#include <mutex>
#include <string>
#include <vector>

#include "amos/camera/openni2_convert.h"
#include "amos/core/error.h"
#include "amos/io/newest_frame_slot.h"
#include "amos/io/sequence_recorder.h"

namespace amos::camera {

namespace {

// OpenNI2's extended error of the last call, without its leading tab and trailing newline.
std::string extendedError() {
  std::string text = openni::OpenNI::getExtendedError();
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) return "no details given";
  text = text.substr(first, last - first + 1);
  for (char& c : text) {
    if (c == '\n' || c == '\t') c = ' ';
  }
  return text;
}

std::string devicesFound() {
  openni::Array<openni::DeviceInfo> list;
  openni::OpenNI::enumerateDevices(&list);
  if (list.getSize() == 0) return "OpenNI2 found 0 devices";
  std::string text = fmt::format("OpenNI2 found {} device(s):", list.getSize());
  for (int i = 0; i < list.getSize(); ++i) {
    text += fmt::format(" {}'{}' ({} {})", i > 0 ? ", " : "", list[i].getUri(), list[i].getVendor(),
                        list[i].getName());
  }
  return text;
}

const char* sensorName(openni::SensorType type) { return type == openni::SENSOR_COLOR ? "colour" : "depth"; }

std::string modeText(const openni::VideoMode& m) {
  return fmt::format("{}x{}@{} format {}", m.getResolutionX(), m.getResolutionY(), m.getFps(),
                     static_cast<int>(m.getPixelFormat()));
}

// OpenNI::initialize / shutdown as a scope (OpenNI2 counts them, so sources may overlap).
struct OpenNIScope {
  OpenNIScope() {
    if (openni::OpenNI::initialize() != openni::STATUS_OK)
      throw core::Error("OpenNI2 could not be initialised: " + extendedError());
  }
  ~OpenNIScope() { openni::OpenNI::shutdown(); }
  OpenNIScope(const OpenNIScope&) = delete;
  OpenNIScope& operator=(const OpenNIScope&) = delete;
};

struct Half {
  double t = 0;
  cv::Mat image;
};

}  // namespace

struct OpenNI2Source::Impl : openni::VideoStream::NewFrameListener, openni::OpenNI::DeviceDisconnectedListener {
  OpenNI2Options options;
  OpenNIScope scope;  // first: initialised before and shut down after everything below
  openni::Device device;
  openni::VideoStream colour, depth;
  std::string description;
  io::NewestFrameSlot slot;
  std::mutex pair_mutex;  // OpenNI2 may call onNewFrame from more than one thread
  std::optional<Half> pending_colour, pending_depth;
  std::size_t paired = 0;
  bool colour_listening = false, depth_listening = false, disconnect_listening = false;

  explicit Impl(const OpenNI2Options& o) : options(o) {
    const char* uri = options.uri.empty() ? openni::ANY_DEVICE : options.uri.c_str();
    if (device.open(uri) != openni::STATUS_OK) {
      const std::string error = extendedError();  // before enumerateDevices overwrites it
      throw core::Error(fmt::format("OpenNI2 could not open {}: {}; {}",
                                    options.uri.empty() ? "a device" : "device '" + options.uri + "'", error,
                                    devicesFound()));
    }
    const openni::DeviceInfo& info = device.getDeviceInfo();
    description = fmt::format("{} {} ({})", info.getVendor(), info.getName(), info.getUri());
    try {
      start();
    } catch (...) {
      stop();
      throw;
    }
    spdlog::info("OpenNI2: {} streaming colour + depth at {}x{}@{}", description, options.width, options.height,
                 options.fps);
  }

  ~Impl() override { stop(); }

  void createStream(openni::VideoStream& stream, openni::SensorType type, openni::PixelFormat format) {
    const char* what = sensorName(type);
    core::require(device.hasSensor(type), fmt::format("OpenNI2: {} has no {} sensor", description, what));
    core::require(stream.create(device, type) == openni::STATUS_OK,
                  fmt::format("OpenNI2: cannot create the {} stream of {}: {}", what, description, extendedError()));
    const openni::Array<openni::VideoMode>& modes = stream.getSensorInfo().getSupportedVideoModes();
    std::vector<std::string> offered;
    for (int i = 0; i < modes.getSize(); ++i) {
      const openni::VideoMode& m = modes[i];
      if (m.getResolutionX() == options.width && m.getResolutionY() == options.height && m.getFps() == options.fps &&
          m.getPixelFormat() == format) {
        core::require(stream.setVideoMode(m) == openni::STATUS_OK,
                      fmt::format("OpenNI2: cannot set the {} mode {} on {}: {}", what, modeText(m), description,
                                  extendedError()));
        if (stream.isPropertySupported(openni::STREAM_PROPERTY_MIRRORING)) stream.setMirroringEnabled(false);
        return;
      }
      offered.push_back(modeText(m));
    }
    throw core::Error(fmt::format("OpenNI2: {} offers no {} mode {}x{}@{} format {}; it offers: {}", description,
                                  what, options.width, options.height, options.fps, static_cast<int>(format),
                                  fmt::join(offered, ", ")));
  }

  void start() {
    createStream(colour, openni::SENSOR_COLOR, openni::PIXEL_FORMAT_RGB888);
    createStream(depth, openni::SENSOR_DEPTH, openni::PIXEL_FORMAT_DEPTH_1_MM);
    core::require(device.isImageRegistrationModeSupported(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR),
                  fmt::format("OpenNI2: {} cannot register depth to colour", description));
    core::require(device.setImageRegistrationMode(openni::IMAGE_REGISTRATION_DEPTH_TO_COLOR) == openni::STATUS_OK,
                  fmt::format("OpenNI2: cannot register depth to colour on {}: {}", description, extendedError()));
    if (device.setDepthColorSyncEnabled(true) != openni::STATUS_OK)
      spdlog::warn("OpenNI2: {} has no colour-depth frame sync ({}); frames are paired by time stamp only",
                   description, extendedError());
    disconnect_listening = openni::OpenNI::addDeviceDisconnectedListener(this) == openni::STATUS_OK;
    colour_listening = colour.addNewFrameListener(this) == openni::STATUS_OK;
    depth_listening = depth.addNewFrameListener(this) == openni::STATUS_OK;
    core::require(colour_listening && depth_listening,
                  fmt::format("OpenNI2: cannot listen to the streams of {}: {}", description, extendedError()));
    for (openni::VideoStream* s : {&depth, &colour}) {
      core::require(s->start() == openni::STATUS_OK,
                    fmt::format("OpenNI2: cannot start the {} stream of {}: {}",
                                s == &colour ? "colour" : "depth", description, extendedError()));
    }
  }

  // Idempotent: stops callbacks first, so nothing below is used after it.
  void stop() {
    slot.close();
    if (colour_listening) colour.removeNewFrameListener(this);
    if (depth_listening) depth.removeNewFrameListener(this);
    if (disconnect_listening) openni::OpenNI::removeDeviceDisconnectedListener(this);
    colour_listening = depth_listening = disconnect_listening = false;
    for (openni::VideoStream* s : {&colour, &depth}) {
      if (s->isValid()) {
        s->stop();
        s->destroy();
      }
    }
    if (device.isValid()) device.close();
  }

  void onNewFrame(openni::VideoStream& stream) override {
    try {
      openni::VideoFrameRef ref;
      if (stream.readFrame(&ref) != openni::STATUS_OK || !ref.isValid()) return;
      const openni::PixelFormat format = ref.getVideoMode().getPixelFormat();
      Half half;
      half.t = deviceSeconds(ref.getTimestamp());
      const bool is_colour = ref.getSensorType() == openni::SENSOR_COLOR;
      if (is_colour) {
        core::require(format == openni::PIXEL_FORMAT_RGB888,
                      fmt::format("OpenNI2: colour frame in format {}, expected RGB888", static_cast<int>(format)));
        half.image = rgb888ToBgr(ref.getData(), ref.getWidth(), ref.getHeight(), ref.getStrideInBytes());
      } else if (ref.getSensorType() == openni::SENSOR_DEPTH) {
        core::require(format == openni::PIXEL_FORMAT_DEPTH_1_MM,
                      fmt::format("OpenNI2: depth frame in format {}, expected 1 mm", static_cast<int>(format)));
        half.image = depthToMetres(ref.getData(), ref.getWidth(), ref.getHeight(), ref.getStrideInBytes(), 0.001);
      } else {
        return;
      }
      std::lock_guard<std::mutex> lock(pair_mutex);
      (is_colour ? pending_colour : pending_depth) = std::move(half);
      if (!pending_colour || !pending_depth) return;
      if (std::abs(pending_colour->t - pending_depth->t) > options.max_pair_dt) {
        // The older one cannot pair with anything that comes later: keep the newer one.
        (pending_colour->t < pending_depth->t ? pending_colour : pending_depth).reset();
        return;
      }
      io::RgbdFrame frame;
      frame.index = paired++;
      frame.timestamp = pending_colour->t;
      frame.bgr = std::move(pending_colour->image);
      frame.depth = std::move(pending_depth->image);
      frame.rgb_file = io::stampText(frame.timestamp) + ".png";
      pending_colour.reset();
      pending_depth.reset();
      slot.put(std::move(frame));
    } catch (...) {
      slot.close(std::current_exception());  // reaches the consumer through next()
    }
  }

  void onDeviceDisconnected(const openni::DeviceInfo* info) override {
    if (info && std::string(info->getUri()) != device.getDeviceInfo().getUri()) return;
    slot.close(std::make_exception_ptr(core::Error(fmt::format("OpenNI2: {} was disconnected", description))));
  }
};

OpenNI2Source::OpenNI2Source(const OpenNI2Options& options) : impl_(std::make_unique<Impl>(options)) {}
OpenNI2Source::~OpenNI2Source() = default;

std::optional<io::RgbdFrame> OpenNI2Source::next() { return impl_->slot.take(); }
void OpenNI2Source::cancel() { impl_->slot.close(); }
std::optional<io::RgbdFrame> OpenNI2Source::poll() { return impl_->slot.tryTake(); }
io::SourceStats OpenNI2Source::stats() const { return impl_->slot.stats(); }
const std::string& OpenNI2Source::description() const { return impl_->description; }

}  // namespace amos::camera
