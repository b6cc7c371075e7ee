#!/usr/bin/env python3
"""Builds the dense static map of a TUM/Bonn-layout folder through the Python module: a mesh and a floor plan.

    dense_map.py SEQUENCE CONFIG OUT [--mode full]

Writes OUT/mesh.ply and, when a floor was found, OUT/occupancy.pgm + OUT/occupancy.yaml: the map fused with the
final trajectory, what `amos-slam run --dense --deterministic` writes for the same folder and settings (the
settings' Dense.* keys apply). Needs a library built with Open3D (amos_slam.dense_available)."""
import argparse
import pathlib
import sys

import numpy as np

import amos_slam


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequence")
    ap.add_argument("config")
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--mode", default="full", choices=["none", "prior", "geometry", "full"])
    args = ap.parse_args()
    if not amos_slam.dense_available:
        sys.exit("error: this amos_slam module was built without the dense map (Open3D)")
    with amos_slam.Slam(args.config, mode=args.mode, deterministic=True, dense=True) as slam:
        for result in slam.track_frames(amos_slam.SequenceFolder(args.sequence)):
            if result.frame % 20 == 19:
                live = slam.dense_snapshot()  # the live surface (tracking poses), or None
                if live is not None:
                    print(f"frame {result.frame}: live surface of {live.cloud.points.shape[0]} points")
    dense = slam.dense_map()  # after finish(): fused anew with the final trajectory
    args.out.mkdir(parents=True, exist_ok=True)
    dense.write_mesh_ply(args.out / "mesh.ply")
    mesh = dense.mesh  # NumPy arrays: vertices (N, 3) float64, triangles (M, 3) uint32, colors (N, 3) uint8
    extent = np.ptp(mesh.vertices, axis=0) if len(mesh.vertices) else np.zeros(3)
    print(f"mesh: {len(mesh.vertices)} vertices, {len(mesh.triangles)} triangles, extent "
          f"{extent[0]:.2f} x {extent[1]:.2f} x {extent[2]:.2f} m")
    if dense.grid is not None:
        dense.write_floor_plan(args.out / "occupancy")
        free = int(np.count_nonzero(dense.grid.cells == 254))
        print(f"floor plan: {dense.grid.cells.shape[1]} x {dense.grid.cells.shape[0]} cells of "
              f"{dense.grid.resolution} m, {free} free")
    else:
        print("floor plan: none (no floor found)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
