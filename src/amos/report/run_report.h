#pragma once
// Writes the outputs of a SLAM run into a folder:
//   trajectory.txt  every tracked frame, TUM format (T_wc)
//   keyframes.txt   the map's keyframes, TUM format
//   map.ply         the map points (ASCII PLY, x y z)
//   stats.json      frame counts, map size, median / p95 ms per stage and per frame, wall time, frames per second,
//                   ATE / RPE when the sequence has ground truth, and the dynamic mask's pixel precision / recall /
//                   IoU when it has ground-truth mover masks, and where the frames came from ("source": kind,
//                   frames delivered / processed / dropped, latency from a frame's arrival to its pose), how its
//                   association file paired RGB and depth ("association": rows, rows_beyond_window, duplicate_rows), the frames
//                   skipped as unreadable by reason ("skipped_frames") and the depth dropouts, and how the run
//                   ended ("end": status complete | interrupted | failed, reason), and how each optional stage
//                   after it went ("optional_stages": name -> status done | failed | interrupted | skipped, reason)
// The main files are written before any optional stage (the dense map's final fusion, report.html) starts;
// stats.json is written again after each such stage. Each file is written under a temporary name and renamed (io/atomic_file.h): a killed run never leaves a
// half-written one.
#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "amos/eval/evaluate.h"
#include "amos/eval/instance_mask_metrics.h"
#include "amos/eval/mask_metrics.h"
#include "amos/io/dataset.h"
#include "amos/io/frame_source.h"
#include "amos/system/slam_system.h"

namespace amos::report {

// Where a run's frames came from and how the SLAM loop kept up with them (see io/frame_source.h).
struct SourceReport {
  std::string kind;  // folder | realtime | openni2
  std::size_t delivered = 0, processed = 0, dropped = 0;
  // Processed frames whose person masks were carried on because the network's segmentation was late (paced and
  // live sources only; a folder run waits for it).
  std::size_t segmentation_late = 0;
  // Per processed frame: from the moment it became available to the moment process() returned its pose, in ms.
  std::vector<double> latency_ms;
  std::string recorded_to;  // --record folder ("" = none)
};

// Processed frames whose depth image was a sensor dropout (io::RgbdFrame::depth_dropout), and how tracking did on
// them from their colour images alone.
struct DepthDropouts {
  std::size_t frames = 0, tracked = 0, lost = 0;  // tracked + lost <= frames (before the map exists: neither)
};

// How a run ended: every frame processed (or --max-frames reached), stopped from outside (a signal), or ended by a
// failure (an unreadable frame with --strict, a worker thread's error). The outputs are those of the frames
// processed until then in every case.
struct RunEnd {
  enum class Status { kComplete, kInterrupted, kFailed };
  Status status = Status::kComplete;
  std::string reason;  // why it ended early ("SIGINT", the error's message); empty when complete
};
// "complete" | "interrupted" | "failed"
const char* toString(RunEnd::Status status);

// A stage after the main outputs are written, which the run's result does not depend on: the dense map's final
// fusion and files, report.html. Its failure is a warning in the summary and in stats.json, not the run's.
struct OptionalStage {
  enum class Status { kDone, kFailed, kInterrupted, kSkipped };
  Status status = Status::kDone;
  std::string reason;  // why it failed, was interrupted or skipped; empty when done
};
// "done" | "failed" | "interrupted" | "skipped"
const char* toString(OptionalStage::Status status);

struct RunInfo {
  std::string sequence, config, mode;
  bool deterministic = false;
  double wall_time_s = 0;
  std::optional<eval::EvaluationResult> evaluation;
  // The dynamic front end's per-stage times (merged into "stages") and, per frame, the fraction of extracted
  // keypoints its mask removed. Null / empty in mode none.
  const core::StageTimes* front_end_times = nullptr;
  std::vector<double> removed_fractions;
  // The final dynamic mask against the union of the ground-truth movers, over the frames where the front end
  // produced a mask; absent without ground-truth masks or in mode none.
  std::optional<eval::MaskAccuracy> mask_accuracy;
  // The same per ground-truth instance (recall and precision while it moves, what stays marked while it rests;
  // eval/instance_mask_metrics.h); written as mask_accuracy.instances.
  std::vector<eval::InstanceAccuracy> instance_accuracy;
  // Time spent on --save-masks outputs and mask scoring (not part of wall_time_s).
  double mask_outputs_s = 0;
  std::optional<SourceReport> source;  // absent when the caller did not read frames from a FrameSource
  // The sequence's association file (io::SequenceIndex::association); absent for a live camera or when the frames
  // were associated from rgb.txt + depth.txt without repeated rows.
  std::optional<io::AssociationStats> association;
  io::SkippedFrames skipped_frames;    // frames the source could not read, by reason
  DepthDropouts depth_dropouts;
  RunEnd end;
  // More sections of stats.json, by name, from the run's observers (e.g. "dense": run/dense_observer.h).
  nlohmann::json sections = nlohmann::json::object();
  // The optional stages that ran or were meant to, by name ("dense", "report"), in stats.json's "optional_stages".
  std::map<std::string, OptionalStage> optional_stages;
};

nlohmann::json toJson(const SourceReport& source);
// {"file", "rows", "rows_beyond_window", "window_s"}
nlohmann::json toJson(const io::AssociationStats& association);

nlohmann::json statsJson(const system::SlamStats& stats, const core::StageTimes& times, const RunInfo& info);
void writeMapPly(const std::string& path, const std::vector<Eigen::Vector3d>& points);
// Creates `dir` if needed; throws core::Error naming the file that cannot be written.
void writeRunOutputs(const std::string& dir, const system::SlamSystem& slam, const RunInfo& info);
// stats.json alone (again, after an optional stage); throws core::Error naming it when it cannot be written.
void writeStatsJson(const std::string& dir, const system::SlamSystem& slam, const RunInfo& info);

}  // namespace amos::report
