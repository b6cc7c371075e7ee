#include "amos/config/key_bounds.h"

#include <algorithm>
#include <functional>
#include <map>
#include <string>

namespace amos::config {

namespace {

// What the upper bound is measured against.
enum class Upper { kFixed, kImageSide, kHalfImage, kImageCells };

struct Bound {
  double low;
  double high;  // for kFixed
  Upper upper;
  const char* reason;
};

// Reasons shared by many keys.
constexpr const char* kCount = "a count that sizes memory or work: at most 100000";
constexpr const char* kShare = "a share";
constexpr const char* kRatio = "a ratio of best to second-best distance";
constexpr const char* kHamming = "a Hamming distance of 256-bit ORB descriptors";
constexpr const char* kPixels = "a distance in pixels, at most the image's larger side";
constexpr const char* kMargin = "a margin of half the image or more leaves nothing inside";
constexpr const char* kKeyFrames = "a number of keyframes, at most 10000";
constexpr const char* kFrames = "a number of frames held or waited for, at most 1000";
constexpr const char* kIterations = "iterations bound the time of one solve: at most 10000";
constexpr const char* kChi2 = "a chi-square outlier threshold of 2 or 3 degrees of freedom";
constexpr const char* kSigmas = "a number of standard deviations, at most 100";
constexpr const char* kDegrees = "an angle in degrees";
constexpr const char* kSeed = "any 32-bit seed";
constexpr const char* kDepth = "a depth within any RGB-D sensor's range (m)";
constexpr const char* kThreads = "threads: at most 256";

constexpr double kMaxCount = 100000;
constexpr double kMaxSeed = 4294967295.0;

Bound fixed(double low, double high, const char* reason) { return {low, high, Upper::kFixed, reason}; }
Bound count(double low = 0) { return fixed(low, kMaxCount, kCount); }
Bound share() { return fixed(0, 1, kShare); }
Bound pixels(double low = 0) { return {low, 0, Upper::kImageSide, kPixels}; }
Bound margin(double low = 0) { return {low, 0, Upper::kHalfImage, kMargin}; }

// clang-format off
const std::map<std::string, Bound>& table() {
  static const std::map<std::string, Bound> bounds = {
      {"Camera.fx", fixed(1, 1e5, "a focal length in pixels")},
      {"Camera.fy", fixed(1, 1e5, "a focal length in pixels")},
      {"Camera.cx", fixed(0, 16384, "a principal point inside the largest image")},
      {"Camera.cy", fixed(0, 16384, "a principal point inside the largest image")},
      {"Camera.k1", fixed(-100, 100, "a radial distortion coefficient of a real lens")},
      {"Camera.k2", fixed(-100, 100, "a radial distortion coefficient of a real lens")},
      {"Camera.k3", fixed(-100, 100, "a radial distortion coefficient of a real lens")},
      {"Camera.p1", fixed(-1, 1, "a tangential distortion coefficient of a real lens")},
      {"Camera.p2", fixed(-1, 1, "a tangential distortion coefficient of a real lens")},
      {"Camera.width", fixed(16, 16384, "an image side in pixels, a frame held in memory")},
      {"Camera.height", fixed(16, 16384, "an image side in pixels, a frame held in memory")},
      {"Camera.fps", fixed(0.01, 1000, "a frame rate (Hz)")},
      {"Camera.bf", fixed(0.001, 1e5, "baseline (m, at most 1) times fx")},
      {"ThDepth", fixed(0.001, 1e5, "a close/far threshold in baselines")},
      {"DepthMapFactor", fixed(100, 65535, "raw units per metre: a centimetre resolved, a metre within 16 bits")},

      {"ORBextractor.nFeatures", fixed(1, kMaxCount, kCount)},
      {"ORBextractor.scaleFactor", fixed(1.01, 2, "a pyramid scale above 1, at most an octave")},
      {"ORBextractor.nLevels", fixed(1, 32, "pyramid levels, each an image held in memory")},
      {"ORBextractor.iniThFAST", fixed(1, 255, "a FAST threshold is a difference of 8-bit grey levels")},
      {"ORBextractor.minThFAST", fixed(1, 255, "a FAST threshold is a difference of 8-bit grey levels")},

      {"Tracking.initMinDepthPoints", count(1)},
      {"Tracking.motionSearchRadius", pixels(1)},
      {"Tracking.motionMinMatches", count()},
      {"Tracking.minMapMatches", count()},
      {"Tracking.referenceMinMatches", count()},
      {"Tracking.localSearchRadius", pixels()},
      {"Tracking.relocSearchRadius", pixels()},
      {"Tracking.localMinInliers", count()},
      {"Tracking.relocMinInliers", count()},
      {"Tracking.maxLocalKeyFrames", fixed(1, 10000, kKeyFrames)},
      {"Tracking.maxFrames", fixed(1, kMaxCount, "a number of frames")},
      {"Tracking.minFrames", fixed(0, kMaxCount, "a number of frames")},
      {"Tracking.keyFrameRefRatio", share()},
      {"Tracking.keyFrameMinRotation", fixed(0, 180, kDegrees)},
      {"Tracking.keyFrameMinBaseline", fixed(0, 10, "a share of the median depth, at most 10")},
      {"Tracking.keyFrameMoverShare", share()},
      {"Tracking.keyFrameViewRotation", fixed(0, 180, kDegrees)},
      {"Tracking.keyFrameViewBaseline", fixed(0, 10, "a share of the median depth, at most 10")},
      {"Tracking.closeTrackedMax", count()},
      {"Tracking.closeUntrackedMin", count()},
      {"Tracking.newPointsMin", count()},
      {"Tracking.voPointsMin", count()},
      {"Tracking.recoveryFrames", fixed(0, kMaxCount, "a number of frames")},
      {"Tracking.recoverySearchRadius", pixels()},
      {"Tracking.chi2Mono", fixed(0.01, 1000, kChi2)},
      {"Tracking.chi2Stereo", fixed(0.01, 1000, kChi2)},
      {"Tracking.poseRounds", fixed(1, 100, "optimisation rounds, at most 100")},
      {"Tracking.poseIterations", fixed(1, 10000, kIterations)},
      {"Tracking.poseRobustRounds", fixed(0, 100, "optimisation rounds, at most 100")},
      {"Matching.thHigh", fixed(0, 256, kHamming)},
      {"Matching.thLow", fixed(0, 256, kHamming)},
      {"Matching.localRatio", fixed(0, 1, kRatio)},
      {"Matching.bruteForceRatio", fixed(0, 1, kRatio)},
      {"Relocalization.candidates", fixed(1, 10000, kKeyFrames)},
      {"Relocalization.minMatches", count()},
      {"Relocalization.matchRatio", fixed(0, 1, kRatio)},
      {"Relocalization.minInliers", count()},
      {"Relocalization.reprojectionThreshold", pixels()},
      {"Relocalization.ransacIterations", fixed(1, 1e6, "RANSAC iterations bound the time of a relocalisation")},
      {"Relocalization.seed", fixed(0, kMaxSeed, kSeed)},

      {"Mapping.covisibilityMinWeight", count(1)},
      {"Mapping.recentFoundRatio", share()},
      {"Mapping.recentMinObservations", fixed(0, 10000, "observations, each by a keyframe")},
      {"Mapping.redundantRatio", share()},
      {"Mapping.redundantObservers", fixed(1, 10000, kKeyFrames)},
      {"Mapping.triangulationNeighbors", fixed(1, 10000, kKeyFrames)},
      {"Mapping.triangulationMaxDistance", fixed(0, 256, kHamming)},
      {"Mapping.triangulationRatio", fixed(0, 1, kRatio)},
      {"Mapping.maxCosParallax", fixed(0, 1, "the cosine of an angle under 90 degrees")},
      {"Mapping.fuseNeighbors", fixed(0, 10000, kKeyFrames)},
      {"Mapping.fuseSecondNeighbors", fixed(0, 10000, kKeyFrames)},
      {"Mapping.fuseRadius", pixels()},
      {"Mapping.fuseMaxDistance", fixed(0, 256, kHamming)},
      {"Mapping.dynamicCullMinHits", count(1)},
      {"Mapping.dynamicCullRatio", share()},
      {"LocalBA.iterationsRobust", fixed(0, 10000, kIterations)},
      {"LocalBA.iterationsRefine", fixed(0, 10000, kIterations)},
      {"LocalBA.maxKeyFrames", fixed(0, 10000, kKeyFrames)},
      {"LocalBA.chi2Mono", fixed(0.01, 1000, kChi2)},
      {"LocalBA.chi2Stereo", fixed(0.01, 1000, kChi2)},
      {"LocalBA.threads", fixed(1, 256, kThreads)},

      {"Loop.essentialMinWeight", count(1)},
      {"Loop.poseGraphIterations", fixed(1, 10000, kIterations)},
      {"Loop.minKeyFrames", fixed(0, kMaxCount, kKeyFrames)},
      {"Loop.minKeyFrameGap", fixed(0, kMaxCount, kKeyFrames)},
      {"Loop.candidates", fixed(1, 10000, kKeyFrames)},
      {"Loop.minMatches", count()},
      {"Loop.matchRatio", fixed(0, 1, kRatio)},
      {"Loop.minInliers", count()},
      {"Loop.consistency", fixed(0, 1000, kKeyFrames)},
      {"Loop.singleKeyFrameInliers", count()},
      {"Loop.reprojectionThreshold", pixels()},

      {"Dynamic.priorMaskedExtractionCoverage", share()},
      {"Dynamic.Prior.interval", fixed(1, 1000, kFrames)},
      {"Dynamic.Prior.lag", fixed(0, 1000, kFrames)},
      {"Dynamic.Prior.detectEvery", fixed(1, 1000, "segmentations between two detections, at most 1000")},
      {"Dynamic.Prior.minTracks", count()},
      {"Dynamic.Prior.holdMissed", fixed(0, 1000, "segmentations a person is carried on, at most 1000")},
      {"Dynamic.Superpixel.count", {1, 0, Upper::kImageCells, "superpixels of at least 4 x 4 pixels of the image"}},
      {"Dynamic.Superpixel.scale", fixed(0.05, 1, "a fraction of the image size")},
      {"Dynamic.Superpixel.colourScale", fixed(0.01, 1000, "a Lab colour distance")},
      {"Dynamic.Superpixel.depthScale", fixed(0.001, 100, kDepth)},
      {"Dynamic.Superpixel.iterations", fixed(1, 1000, "SLIC rounds, at most 1000")},
      {"Dynamic.Cluster.count", fixed(1, 10000, "k-means clusters, at most 10000")},
      {"Dynamic.Cluster.depthScale", fixed(0.001, 100, kDepth)},
      {"Dynamic.Cluster.maxIterations", fixed(1, 10000, kIterations)},
      {"Dynamic.Cluster.seed", fixed(0, kMaxSeed, kSeed)},
      {"Dynamic.Corners.maxCorners", count(1)},
      {"Dynamic.Corners.qualityLevel", fixed(1e-6, 1, "a share of the best corner's response")},
      {"Dynamic.Corners.minDistance", pixels()},
      {"Dynamic.Corners.detectionScale", fixed(0.05, 1, "a fraction of the image size")},
      {"Dynamic.LK.window", margin(3)},
      {"Dynamic.LK.pyramidLevels", fixed(0, 10, "pyramid levels: 2^10 shrinks any image to a few pixels")},
      {"Dynamic.LK.maxIterations", fixed(1, 10000, kIterations)},
      {"Dynamic.LK.epsilon", fixed(0, 10, "a step in pixels")},
      {"Dynamic.LK.forwardBackwardThreshold", pixels()},
      {"Dynamic.Reprojection.cauchyScale", fixed(0.001, 1000, "a scale in pixels")},
      {"Dynamic.Reprojection.threshold", pixels()},
      {"Dynamic.Reprojection.minPoints", count(1)},
      {"Dynamic.Reprojection.maxDepth", fixed(0.1, 100, kDepth)},
      {"Dynamic.Reprojection.depthEdgeRatio", share()},
      {"Dynamic.Reprojection.refitMinPoints", count()},
      {"Dynamic.Reprojection.confirmSigmas", fixed(0, 100, kSigmas)},
      {"Dynamic.Reprojection.confirmThreshold", pixels()},
      {"Dynamic.Epipolar.ransacThreshold", pixels()},
      {"Dynamic.Epipolar.threshold", pixels()},
      {"Dynamic.Epipolar.confidence", fixed(0, 1, "a probability")},
      {"Dynamic.Epipolar.maxIterations", fixed(1, 1e6, "RANSAC iterations bound the time of a frame")},
      {"Dynamic.Epipolar.minDynamicPoints", count()},
      {"Dynamic.Epipolar.minFitPoints", count()},
      {"Dynamic.Epipolar.seed", fixed(0, kMaxSeed, kSeed)},
      {"Dynamic.Boundary.radius", pixels()},
      {"Dynamic.Boundary.borderMargin", margin()},
      {"Dynamic.Depth.sampleStep", margin(1)},
      {"Dynamic.Depth.noiseBase", fixed(0, 1, "a depth noise (m)")},
      {"Dynamic.Depth.noiseQuadratic", fixed(0, 1, "a depth noise growth (1/m)")},
      {"Dynamic.Depth.noiseOffset", fixed(0, 100, kDepth)},
      {"Dynamic.Depth.maxDepth", fixed(0.1, 100, kDepth)},
      {"Dynamic.Depth.sigmas", fixed(0, 100, kSigmas)},
      {"Dynamic.Depth.minResidual", fixed(0, 100, kDepth)},
      {"Dynamic.Depth.minRelativeResidual", share()},
      {"Dynamic.Depth.minSamples", count(1)},
      {"Dynamic.Depth.violationSigmas", fixed(0, 100, kSigmas)},
      {"Dynamic.Depth.violationShare", share()},
      {"Dynamic.Depth.minViolations", count()},
      {"Dynamic.Depth.unscoredClusterSuperpixels", count()},
      {"Dynamic.Depth.baselineFrames", fixed(0, 1000, kFrames)},
      {"Dynamic.Depth.baselineRelativeResidual", share()},
      {"Dynamic.Depth.clusterShare", share()},
      {"Dynamic.BaselineTracks.sigmas", fixed(0, 100, kSigmas)},
      {"Dynamic.BaselineTracks.minMotion", pixels()},
      {"Dynamic.BaselineTracks.minVotes", count()},
      {"Dynamic.BaselineTracks.clusterShare", share()},
      {"Dynamic.BaselineTracks.growDissimilarity", fixed(0, 1000, "an Eq. 1 dissimilarity")},
      {"Dynamic.RigidMovers.minInliers", fixed(3, kMaxCount, "a rigid motion needs 3 points; a count of points")},
      {"Dynamic.RigidMovers.inlierPx", pixels()},
      {"Dynamic.RigidMovers.maxMovers", fixed(0, 100, "rigid motions fitted, at most 100")},
      {"Dynamic.RigidMovers.sampleStep", margin(1)},
      {"Dynamic.RigidMovers.minSeparation", pixels()},
      {"Dynamic.RigidMovers.intensityMargin", fixed(0, 255, "a difference of 8-bit grey levels")},
      {"Dynamic.RigidMovers.minSamples", count(1)},
      {"Dynamic.RigidMovers.regionReach", pixels()},
      {"Dynamic.RigidMovers.minGradient", fixed(0, 255, "a gradient of 8-bit grey levels per pixel")},
      {"Dynamic.InitialPose.inlierThreshold", pixels()},
      {"Dynamic.InitialPose.keyframeMaxPoints", count()},

      {"Segmentation.inputSize", fixed(32, 2048, "the side of a network input held in memory")},
      {"Segmentation.maskInputSize", fixed(64, 256, "the side of the mask network's input")},
      {"Segmentation.scoreThreshold", fixed(0, 1, "a probability")},
      {"Segmentation.nmsIou", fixed(0, 1, "an intersection over union")},
      {"Segmentation.boxWidenX", fixed(0, 10, "a share of the box, at most 10")},
      {"Segmentation.boxWidenY", fixed(0, 10, "a share of the box, at most 10")},
      {"Segmentation.carriedBoxWidenX", fixed(0, 10, "a share of the box, at most 10")},
      {"Segmentation.carriedBoxWidenY", fixed(0, 10, "a share of the box, at most 10")},
      {"Segmentation.maskThreshold", fixed(0, 1, "a probability")},
      {"Segmentation.borderCropAspect", fixed(0, 10, "a width-to-height ratio, at most 10")},
      {"Segmentation.minMaskFill", share()},
      {"Segmentation.depthTolerance", fixed(0, 100, kDepth)},
      {"Segmentation.maxInstances", fixed(0, 1000, "instances, each a mask held in memory: at most 1000")},
      {"Segmentation.dilationSize", margin()},
      {"Segmentation.threads", fixed(0, 256, kThreads)},
  };
  return bounds;
}
// clang-format on

std::function<double()> upperOf(const Bound& bound, const core::CameraIntrinsics& camera) {
  switch (bound.upper) {
    case Upper::kImageSide:
      return [&camera] { return static_cast<double>(std::max(camera.width, camera.height)); };
    case Upper::kHalfImage:
      return [&camera] { return std::min(camera.width, camera.height) / 2.0; };
    case Upper::kImageCells:
      return [&camera] { return static_cast<double>(camera.width) * camera.height / 16.0; };
    case Upper::kFixed:
      break;
  }
  const double high = bound.high;
  return [high] { return high; };
}

}  // namespace

void applyKeyBounds(std::vector<KeySection>& sections, const core::CameraIntrinsics& camera) {
  for (KeySection& section : sections) {
    for (SettingsKey& key : section.keys) {
      const auto found = table().find(key.name());
      if (found == table().end()) continue;
      key.within(found->second.low, upperOf(found->second, camera), found->second.reason);
    }
  }
}

}  // namespace amos::config
