// amos-slam segment: prior-dynamic-object masks for every frame of a sequence (TUM layout or a folder of images).
// Writes OUT/masks/<image name> (8-bit PNG, 255 = prior dynamic object, undilated), OUT/overlays/<image name>,
// OUT/contact_sheet.png and OUT/segment_summary.json. All the work is in amos::dynamic.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <deque>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <sstream>

#include "amos/config/settings.h"
#include "amos/run/settings_sections.h"
#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/segmentation/segment_masks.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/segmentation/segmenter_classes.h"
#include "amos/segmentation/segmenter_factory.h"
#include "amos/io/dataset.h"
#include "amos/io/image_codecs.h"
#include "commands.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

struct SegmentArgs {
  std::string sequence, models, output, settings;
  segmentation::SegmenterOptions segmenter;
  std::string classes = "person";
  double depth_factor = 5000.0;
  std::size_t limit = 0, every = 1, sheet_frames = 12;
  bool overlays = true;
};

struct InputFrame {
  std::string rgb_file, depth_file;  // depth_file empty for plain image folders
};

bool isImageFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".ppm" || ext == ".tif" ||
         ext == ".tiff";
}

// rgb.txt without depth: `timestamp file` lines, '#' comments.
std::vector<InputFrame> readRgbList(const fs::path& dir) {
  std::ifstream in(dir / "rgb.txt");
  std::vector<InputFrame> frames;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string stamp, file;
    if (fields >> stamp >> file) frames.push_back({(dir / file).string(), ""});
  }
  return frames;
}

// A TUM/Bonn sequence (rgb.txt; with depth when there is depth.txt or an association file) or a folder of images.
std::vector<InputFrame> listFrames(const std::string& sequence) {
  const fs::path dir(sequence);
  core::require(fs::is_directory(dir), fmt::format("--sequence '{}' is not a folder", sequence));
  std::vector<InputFrame> frames;
  if (fs::is_regular_file(dir / "rgb.txt")) {
    const bool has_depth = fs::is_regular_file(dir / "depth.txt") || fs::is_regular_file(dir / "associations.txt") ||
                           fs::is_regular_file(dir / "associate.txt");
    if (has_depth) {
      for (const auto& f : io::indexSequence(sequence).frames) frames.push_back({f.rgb_file, f.depth_file});
    } else {
      frames = readRgbList(dir);
    }
  } else {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && isImageFile(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) frames.push_back({f.string(), ""});
  }
  core::require(!frames.empty(), fmt::format("--sequence '{}' has no images (neither rgb.txt nor image files)", sequence));
  return frames;
}

// masks/<name>: the image's own name, with a .png extension when it had another one (masks are always PNG).
std::string maskName(const std::string& rgb_file) {
  fs::path name = fs::path(rgb_file).filename();
  if (name.extension() != ".png") name.replace_extension(".png");
  return name.string();
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

int runSegment(SegmentArgs args) {
  args.segmenter.classes = splitList(args.classes);
  const bool needs_depth = std::any_of(args.segmenter.classes.begin(), args.segmenter.classes.end(),
                                       [](const std::string& c) { return c != "person"; });
  segmentation::ModelSources sources;
  sources.cli_dir = args.models;
  if (!args.settings.empty()) sources.settings_dir = run::loadSettings(args.settings).segmentation.models_dir;
  sources.environment = segmentation::processEnvironment();

  // Models are loaded and checked before any frame is read.
  auto segmenter = segmentation::createSegmenter(args.segmenter, sources, segmentation::builtinSegmenterFactory());
  std::vector<InputFrame> frames = listFrames(args.sequence);
  if (args.every > 1) {
    std::vector<InputFrame> kept;
    for (std::size_t i = 0; i < frames.size(); i += args.every) kept.push_back(frames[i]);
    frames.swap(kept);
  }
  if (args.limit > 0 && frames.size() > args.limit) frames.resize(args.limit);

  const fs::path out(args.output);
  fs::create_directories(out / "masks");
  if (args.overlays) fs::create_directories(out / "overlays");
  spdlog::info("segment: {} frames from {} -> {}", frames.size(), args.sequence, out.string());

  // Frames picked for the contact sheet: evenly spread over the sequence.
  std::vector<std::size_t> sheet_indices;
  for (std::size_t k = 0; k < std::min(args.sheet_frames, frames.size()); ++k)
    sheet_indices.push_back(k * frames.size() / std::min(args.sheet_frames, frames.size()));
  std::vector<cv::Mat> sheet_tiles;
  std::vector<std::string> sheet_captions;

  segmentation::SegmentationWorker worker(std::move(segmenter), args.segmenter.dilation, 2);
  struct Pending {
    std::size_t index;
    cv::Mat bgr;
    std::future<segmentation::SegmentationResult> result;
  };
  std::deque<Pending> pending;
  core::StageTimes times;
  std::size_t instances = 0, frames_with_objects = 0, done = 0;
  const std::size_t report_every = std::max<std::size_t>(1, frames.size() / 20);
  core::Stopwatch wall;

  // Writes the oldest pending frame's outputs; reading the next frames overlaps with its segmentation.
  auto finishOldest = [&] {
    Pending p = std::move(pending.front());
    pending.pop_front();
    const segmentation::SegmentationResult r = p.result.get();
    times.add("segment", r.segment_ms);
    instances += r.instances.size();
    frames_with_objects += r.instances.empty() ? 0 : 1;
    const std::string name = maskName(frames[p.index].rgb_file);
    io::writeImage((out / "masks" / name).string(), r.mask);
    const bool on_sheet = std::find(sheet_indices.begin(), sheet_indices.end(), p.index) != sheet_indices.end();
    if (args.overlays || on_sheet) {
      const cv::Mat overlay = segmentation::drawOverlay(p.bgr, r.instances);
      if (args.overlays) io::writeImage((out / "overlays" / name).string(), overlay);
      if (on_sheet) {
        sheet_tiles.push_back(overlay);
        sheet_captions.push_back(fmt::format("#{} {}", p.index, fs::path(frames[p.index].rgb_file).filename().string()));
      }
    }
    ++done;
    if (done % report_every == 0 || done == frames.size())
      spdlog::info("segment: {:>5}/{} frames ({:3.0f}%), {:.1f} frames/s, {:.1f} ms/frame median", done, frames.size(),
                   100.0 * done / frames.size(), 1000.0 * done / wall.elapsedMs(),
                   core::percentile(times.samples("segment"), 0.5));
  };

  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::Mat bgr = io::readImage(frames[i].rgb_file, io::kReadColor);
    core::require(!bgr.empty(), fmt::format("cannot read image '{}'", frames[i].rgb_file));
    cv::Mat depth;
    if (needs_depth && !frames[i].depth_file.empty()) {
      io::ReaderOptions reader;
      reader.depth_factor = args.depth_factor;
      reader.width = bgr.cols;
      reader.height = bgr.rows;
      depth = io::loadRgbdFrame({0, 0, frames[i].rgb_file, frames[i].depth_file}, reader, i).depth;
    }
    pending.push_back({i, bgr, worker.submit(i, bgr, depth)});
    if (pending.size() > 2) finishOldest();
  }
  while (!pending.empty()) finishOldest();

  if (!sheet_tiles.empty()) {
    const fs::path sheet = out / "contact_sheet.png";
    io::writeImage(sheet.string(), segmentation::contactSheet(sheet_tiles, sheet_captions, 4, 320));
    spdlog::info("segment: contact sheet of {} frames in {}", sheet_tiles.size(), sheet.string());
  }
  const auto summary = times.summary()["segment"];
  nlohmann::json j;
  j["sequence"] = args.sequence;
  j["frames"] = frames.size();
  j["backend"] = worker.segmenter().name();
  j["input_size"] = args.segmenter.input_size;
  j["classes"] = args.segmenter.classes;
  j["score_threshold"] = args.segmenter.score_threshold;
  j["opencv_threads"] = cv::getNumThreads();
  j["instances"] = instances;
  j["frames_with_objects"] = frames_with_objects;
  j["segment_ms"] = {{"median", summary.median_ms}, {"p95", summary.p95_ms}, {"mean", summary.mean_ms},
                     {"max", summary.max_ms}};
  j["wall_s"] = wall.elapsedMs() / 1000.0;
  std::ofstream((out / "segment_summary.json").string()) << j.dump(2) << "\n";
  spdlog::info("segment: done, {} instances in {} of {} frames, median {:.1f} ms/frame; masks in {}", instances,
               frames_with_objects, frames.size(), summary.median_ms, (out / "masks").string());
  return 0;
}

}  // namespace

void addSegmentCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SegmentArgs>();
  auto* cmd = app.add_subcommand(
      "segment", "Write prior-dynamic-object masks (people by default) for every frame of a sequence");
  cmd->add_option("--sequence", args->sequence, "TUM/Bonn-layout sequence folder or a folder of images")
      ->required();
  cmd->add_option("--output", args->output, "Output folder (masks/, overlays/, contact_sheet.png)")->required();
  cmd->add_option("--models", args->models,
                  "Folder with the ONNX models (else Segmentation.modelsDir, $AMOS_MODELS, ./models, "
                  "../shared/models)");
  cmd->add_option("--config,--settings", args->settings,
                  "Settings file (configs/*.yaml), for Segmentation.modelsDir (--settings: its former name)");
  cmd->add_option("--backend", args->segmenter.backend, "Segmentation backend")->capture_default_str();
  cmd->add_option("--input-size", args->segmenter.input_size, "Detector input size: 320 or 416")
      ->capture_default_str();
  cmd->add_option("--classes", args->classes, "Comma-separated COCO classes to mask, e.g. person,chair,dog")
      ->capture_default_str();
  cmd->add_option("--score", args->segmenter.score_threshold, "Detector score threshold")->capture_default_str();
  cmd->add_option("--threads", args->segmenter.threads, "OpenCV threads (0 = OpenCV default)")->capture_default_str();
  cmd->add_option("--depth-factor", args->depth_factor, "Raw depth / factor = metres (non-person classes only)")
      ->capture_default_str();
  cmd->add_option("--every", args->every, "Segment every n-th frame")->capture_default_str();
  cmd->add_option("--limit", args->limit, "Stop after this many frames (0 = all)")->capture_default_str();
  cmd->add_option("--contact-sheet", args->sheet_frames, "Frames in contact_sheet.png (0 = none)")
      ->capture_default_str();
  cmd->add_flag("!--no-overlays", args->overlays, "Do not write overlays/");
  cmd->callback([args, &exit_code] {
    core::require(args->every >= 1, "--every must be >= 1");
    exit_code = runSegment(*args);
  });
}

}  // namespace amos::app
