#!/usr/bin/env python3
"""show_mask.py SEQUENCE CONFIG FRAME OVERLAY_PNG [MODE]

Tracks a TUM/Bonn-layout folder up to frame FRAME (0-based) and writes that frame's dynamic mask as a PNG overlay:
the colour image with the pixels judged dynamic tinted red. Needs python3-opencv (cv2) to write the PNG."""
import sys

import cv2
import numpy as np

import amos_slam


def overlay(bgr, mask):
    out = bgr.copy()
    red = np.zeros_like(bgr)
    red[..., 2] = 255
    dynamic = mask > 0
    out[dynamic] = (0.5 * bgr[dynamic] + 0.5 * red[dynamic]).astype(np.uint8)
    return out


def main(argv):
    if len(argv) not in (5, 6):
        print(__doc__.strip().splitlines()[0], file=sys.stderr)
        return 2
    sequence, config, frame_index, out = argv[1], argv[2], int(argv[3]), argv[4]
    folder = amos_slam.SequenceFolder(sequence)
    if not 0 <= frame_index < len(folder):
        print(f"error: FRAME {frame_index}: the sequence has {len(folder)} frames", file=sys.stderr)
        return 2
    with amos_slam.Slam(config, mode=argv[5] if len(argv) == 6 else "full") as slam:
        for i in range(frame_index + 1):
            frame = folder.read(i)
            result = slam.track(frame.bgr, frame.depth, frame.timestamp)
    mask = result.dynamic_mask
    if not cv2.imwrite(out, overlay(frame.bgr, mask)):
        print(f"error: cannot write {out}", file=sys.stderr)
        return 1
    print(f"frame {frame_index}: {result.state.name}, {np.count_nonzero(mask)} of {mask.size} pixels dynamic, "
          f"{result.keypoints_removed} of {result.keypoints} keypoints removed -> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
