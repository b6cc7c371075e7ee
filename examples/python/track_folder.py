#!/usr/bin/env python3
"""Tracks a TUM/Bonn-layout folder through the Python module and writes its trajectory in the TUM format.

    track_folder.py SEQUENCE CONFIG TRAJECTORY_OUT [--mode full] [--not-deterministic]

Deterministic by default: the trajectory is then the one `amos-slam run --deterministic` writes for the same
folder, byte for byte. Prints the frames per second of the tracking loop (reading the images included)."""
import argparse
import sys
import time

import amos_slam


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequence")
    ap.add_argument("config")
    ap.add_argument("trajectory_out")
    ap.add_argument("--mode", default="full", choices=["none", "prior", "geometry", "full"])
    ap.add_argument("--not-deterministic", action="store_true",
                    help="local mapping in its own time, as a run without --deterministic")
    args = ap.parse_args()
    folder = amos_slam.SequenceFolder(args.sequence)  # frames decoded ahead; a bad frame is skipped and counted
    with amos_slam.Slam(args.config, mode=args.mode, deterministic=not args.not_deterministic) as slam:
        start = time.perf_counter()
        tracked = 0
        # track_frames takes the frames one ahead of the results: the next frame's features are extracted while
        # the current one is tracked (slam.track(frame.bgr, frame.depth, frame.timestamp) would do, a little slower).
        for result in slam.track_frames(folder):
            tracked += result.T_wc is not None
        slam.finish()
        seconds = time.perf_counter() - start
        slam.write_trajectory(args.trajectory_out)
        summary = slam.summary()
    frames = len(folder) - folder.skipped
    print(f"amos_slam {amos_slam.__version__}: {frames} frames ({folder.skipped} skipped), {tracked} tracked, "
          f"{summary.keyframes} keyframes, {frames / seconds:.1f} fps -> {args.trajectory_out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
