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
    slam = amos_slam.Slam(args.config, mode=args.mode, deterministic=not args.not_deterministic)
    folder = amos_slam.SequenceFolder(args.sequence)
    start = time.perf_counter()
    tracked = 0
    more = True

    def submit_next():
        nonlocal more
        frame = folder.next()  # decoded ahead by the folder's own thread; None after the last
        if frame is not None:
            slam.submit(frame["bgr"], frame["depth"], frame["timestamp"])
        more = frame is not None

    # One frame of look-ahead: frame k+1 is submitted (its features are extracted in the library's threads) before
    # frame k's result is taken. slam.track(bgr, depth, timestamp) alone would do too, a little slower.
    submit_next()
    while slam.pending() > 0:
        if more:
            submit_next()
        result = slam.next()
        tracked += result.state == amos_slam.TrackingState.OK
    slam.finish()
    seconds = time.perf_counter() - start
    slam.write_trajectory(args.trajectory_out)
    summary = slam.summary()
    print(f"amos_slam {amos_slam.__version__}: {len(folder)} frames, {tracked} tracked, "
          f"{summary['keyframes']} keyframes, {len(folder) / seconds:.1f} fps -> {args.trajectory_out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
