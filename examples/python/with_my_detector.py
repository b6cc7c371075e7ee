#!/usr/bin/env python3
"""with_my_detector.py SEQUENCE CONFIG TRAJECTORY_OUT [--mode none]

Tracks a TUM/Bonn-layout folder with your own detector's masks: whatever it marks as dynamic is left out of
tracking and mapping, merged with what the front end finds itself (in mode none, the front end finds nothing, so
the detector is all there is). Writes the trajectory in the TUM format and prints how many keypoints the masks
removed.

The detector here is a stand-in: on a synthetic sequence (`amos-slam synth`, docs/synthetic.md) it returns the
sequence's own mover masks (masks/, 16-bit instance ids); elsewhere it finds nothing. Replace my_detector with
yours: it takes a frame (BGR uint8 H x W x 3, depth, time stamp) and returns a uint8 H x W mask, 255 = dynamic,
or None."""
import argparse
import pathlib
import sys

import cv2
import numpy as np

import amos_slam


def synthetic_truth_detector(sequence):
    """A detector that knows the answer: the synthetic sequence's instance masks, looked up by time stamp."""
    index = pathlib.Path(sequence) / "masks.txt"
    masks = {}
    if index.exists():
        for line in index.read_text().splitlines():
            if line and not line.startswith("#"):
                stamp, file = line.split()[:2]
                masks[round(float(stamp), 6)] = pathlib.Path(sequence) / file

    def detect(frame):
        file = masks.get(round(frame.timestamp, 6))
        if file is None:
            return None
        ids = cv2.imread(str(file), cv2.IMREAD_UNCHANGED)
        return np.where(ids > 0, 255, 0).astype(np.uint8)

    return detect


def with_masks(frames, detector):
    """The frames, each with its prior mask: (bgr, depth, timestamp, prior_mask) as Slam.track_frames takes them."""
    for frame in frames:
        yield frame.bgr, frame.depth, frame.timestamp, detector(frame)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequence")
    ap.add_argument("config")
    ap.add_argument("trajectory_out")
    ap.add_argument("--mode", default="none", choices=["none", "prior", "geometry", "full"])
    args = ap.parse_args()
    my_detector = synthetic_truth_detector(args.sequence)
    removed = kept = 0
    with amos_slam.Slam(args.config, mode=args.mode, deterministic=True) as slam:
        for result in slam.track_frames(with_masks(amos_slam.SequenceFolder(args.sequence), my_detector)):
            removed += result.keypoints_removed
            kept += result.keypoints - result.keypoints_removed
        slam.finish()
        slam.write_trajectory(args.trajectory_out)
        summary = slam.summary()
    print(f"{summary.frames} frames, {summary.tracked} tracked; the masks removed {removed} keypoints, "
          f"{kept} were used -> {args.trajectory_out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
