"""Tests of the Python module amos_slam (CTest python/*; python/CMakeLists.txt sets the environment):
AMOS_SOURCE_DIR (configs), AMOS_SEQUENCE (a synthetic walking_xyz sequence of 30 frames), PYTHONPATH (the module),
AMOS_BAG_FROM_FOLDER (amos_bag_from_folder, in a build with the ROS part)."""
import gc
import inspect
import logging
import os
import pathlib
import re
import shutil
import subprocess
import tempfile
import threading
import unittest

import numpy as np

import amos_slam

SOURCE = pathlib.Path(os.environ["AMOS_SOURCE_DIR"])
SEQUENCE = pathlib.Path(os.environ["AMOS_SEQUENCE"])
CONFIG = SOURCE / "configs" / "tum3.yaml"

# pybind11 writes each function's signature as the first line(s) of its docstring; a description must follow.
SIGNATURE = re.compile(r"^\s*(\d+\.\s+)?[\w.]+\(.*\)(\s*->\s*.+)?\s*$|^\s*Overloaded function\.\s*$")


def description(obj):
    doc = inspect.getdoc(obj) or ""
    return "\n".join(line for line in doc.splitlines() if not SIGNATURE.match(line)).strip()


def geometry_slam(**kwargs):
    return amos_slam.Slam(CONFIG, mode="geometry", deterministic=True, **kwargs)


class Docstrings(unittest.TestCase):
    OWN_DUNDERS = {"__init__", "__iter__", "__next__", "__len__", "__enter__", "__exit__", "__repr__"}

    def test_every_public_class_method_and_property_has_a_docstring(self):
        missing = []
        for name, cls in vars(amos_slam).items():
            if name.startswith("_"):
                continue
            if inspect.isbuiltin(cls) or inspect.isfunction(cls):
                if not description(cls):
                    missing.append(name)
                continue
            if not inspect.isclass(cls):
                continue
            if not description(cls):
                missing.append(name)
            if hasattr(cls, "__members__"):  # an enumeration: its values are documented in its docstring
                continue
            for attr, value in vars(cls).items():
                if attr.startswith("_") and attr not in self.OWN_DUNDERS:
                    continue
                if not description(value):
                    missing.append(f"{name}.{attr}")
        self.assertEqual(missing, [], "without a docstring")

    def test_help_reads_as_documentation(self):
        self.assertIn("Tracks one frame", amos_slam.Slam.track.__doc__)
        self.assertIn("None when it was not tracked", amos_slam.FrameResult.T_wc.__doc__)


class Tracking(unittest.TestCase):
    def test_context_manager_iteration_and_results(self):
        with geometry_slam() as slam:
            results = list(slam.track_frames(amos_slam.SequenceFolder(SEQUENCE)))
            self.assertFalse(slam.finished)
        self.assertTrue(slam.finished)
        self.assertEqual([r.frame for r in results], list(range(30)))
        self.assertTrue(all(r.state == amos_slam.TrackingState.OK for r in results))
        self.assertEqual(results[3].T_wc.shape, (4, 4))
        self.assertEqual(results[3].dynamic_mask.shape, (480, 640))
        self.assertIn("FrameResult(frame=3", repr(results[3]))
        self.assertEqual(len(slam.trajectory()), 30)
        self.assertIsInstance(slam.trajectory()[0], amos_slam.StampedPose)
        summary = slam.summary()
        self.assertEqual(summary.frames, 30)
        self.assertIn("MapSummary(keyframes=", repr(summary))
        self.assertRegex(repr(slam), r"Slam\(frames=30, .*finished=True\)")
        f = amos_slam.SequenceFolder(SEQUENCE).read(0)
        with self.assertRaisesRegex(RuntimeError, "finish\\(\\) was called"):
            slam.track(f.bgr, f.depth, 1e9)

    def test_track_frames_gives_tracks_results(self):
        folder = amos_slam.SequenceFolder(SEQUENCE)
        frames = [folder.read(i) for i in range(12)]
        with geometry_slam() as one, geometry_slam() as stream:
            for f in frames:
                one.track(f.bgr, f.depth, f.timestamp)
            list(stream.track_frames((f.bgr, f.depth, f.timestamp) for f in frames))
        a, b = one.trajectory(), stream.trajectory()
        self.assertEqual(len(a), 12)
        for p, q in zip(a, b):
            self.assertEqual(p.timestamp, q.timestamp)
            np.testing.assert_array_equal(p.T_wc, q.T_wc)

    def test_an_untracked_frame_has_no_pose(self):
        f = amos_slam.SequenceFolder(SEQUENCE).read(0)
        with geometry_slam() as slam:
            r = slam.track(f.bgr, np.zeros_like(f.depth), f.timestamp)  # no depth: no map can start
        self.assertEqual(r.state, amos_slam.TrackingState.NOT_INITIALIZED)
        self.assertIsNone(r.T_wc)
        self.assertIn("T_wc=None", repr(r))

    def test_keyframes_and_events_are_the_same_kind(self):
        with geometry_slam() as slam:
            list(slam.track_frames(amos_slam.SequenceFolder(SEQUENCE)))
        events, keyframes = slam.take_keyframe_events(), slam.keyframes()
        self.assertGreaterEqual(len(keyframes), 2)
        self.assertTrue(all(isinstance(k, amos_slam.KeyFrame) for k in events + keyframes))
        self.assertEqual({k.id for k in events}, {k.id for k in keyframes})
        self.assertIn("KeyFrame(id=", repr(keyframes[0]))

    def test_paths_may_be_pathlib(self):
        out = pathlib.Path(tempfile.mkdtemp()) / "trajectory.txt"
        with amos_slam.Slam(CONFIG, mode=amos_slam.Mode.NONE) as slam:
            f = amos_slam.SequenceFolder(SEQUENCE).read(0)
            slam.track(f.bgr, f.depth, f.timestamp)
        slam.write_trajectory(out)
        self.assertTrue(out.read_text().strip())
        shutil.rmtree(out.parent)

    def test_calls_from_two_threads(self):
        folder = amos_slam.SequenceFolder(SEQUENCE)
        frames = [folder.read(i) for i in range(10)]
        errors = []
        with geometry_slam() as slam:
            done = threading.Event()

            def poll():
                while not done.is_set():
                    try:
                        slam.summary()
                        slam.trajectory()
                        slam.next()
                    except RuntimeError as e:
                        if "no frame was submitted" not in str(e):
                            errors.append(e)

            other = threading.Thread(target=poll)
            other.start()
            results = [slam.track(f.bgr, f.depth, f.timestamp) for f in frames]
            done.set()
            other.join()
        self.assertEqual(errors, [])
        self.assertEqual([r.frame for r in results], list(range(10)))


class Arguments(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.slam = geometry_slam()
        cls.frame = amos_slam.SequenceFolder(SEQUENCE).read(0)

    @classmethod
    def tearDownClass(cls):
        cls.slam.finish()

    def test_kinds_shapes_and_layouts_are_named(self):
        f, slam = self.frame, self.slam
        cases = [
            (TypeError, "argument 'bgr' must be a numpy array", lambda: slam.track([1, 2], f.depth, 1.0)),
            (TypeError, "argument 'bgr'.*dtype float64", lambda: slam.track(f.bgr.astype(np.float64), f.depth, 1.0)),
            (ValueError, "argument 'bgr'.*shape \\(480, 640\\)",
             lambda: slam.track(f.bgr[..., 0].copy(), f.depth, 1.0)),
            (ValueError, "argument 'bgr'.*not C-contiguous", lambda: slam.track(f.bgr[:, ::-1], f.depth, 1.0)),
            (TypeError, "argument 'depth'.*dtype int32", lambda: slam.track(f.bgr, f.depth.astype(np.int32), 1.0)),
            (ValueError, "argument 'depth'.*shape \\(480, 640, 3\\)",
             lambda: slam.track(f.bgr, f.bgr.astype(np.uint16), 1.0)),
            (TypeError, "argument 'prior_mask'.*dtype bool", lambda: slam.track(f.bgr, f.depth, 1.0, f.depth > 0)),
            (RuntimeError, "argument 'bgr' is 320x240", lambda: slam.track(f.bgr[:240, :320].copy(), f.depth, 1.0)),
            (RuntimeError, "argument 'timestamp' must be finite", lambda: slam.track(f.bgr, f.depth, float("nan"))),
            (RuntimeError, "argument 'timestamp' must be finite", lambda: slam.track(f.bgr, f.depth, float("inf"))),
            (ValueError, "argument 'mode' must be", lambda: amos_slam.Slam(CONFIG, mode="fast")),
            (RuntimeError, "unknown settings key 'Camera.widht'",
             lambda: amos_slam.Slam(CONFIG, mode="none", overrides={"Camera.widht": "1"})),
            (TypeError, "each frame must be", lambda: list(slam.track_frames([42]))),
        ]
        for error, pattern, call in cases:
            with self.subTest(pattern=pattern):
                with self.assertRaisesRegex(error, pattern):
                    call()

    def test_time_stamps_must_increase(self):
        folder = amos_slam.SequenceFolder(SEQUENCE)
        with geometry_slam() as slam:
            a, b = folder.read(0), folder.read(1)
            slam.track(a.bgr, a.depth, a.timestamp)
            with self.assertRaisesRegex(RuntimeError, "argument 'timestamp' must increase"):
                slam.track(b.bgr, b.depth, a.timestamp)
        self.assertEqual(len(slam.trajectory()), 1)


class Folders(unittest.TestCase):
    def test_a_bad_frame_is_skipped_warned_about_and_counted(self):
        work = pathlib.Path(tempfile.mkdtemp())
        seq = work / "seq"
        shutil.copytree(SEQUENCE, seq)
        damaged = pathlib.Path(amos_slam.SequenceFolder(seq).read(4).rgb_file)
        damaged.write_bytes(b"not a png")
        folder = amos_slam.SequenceFolder(seq)
        with self.assertLogs("amos_slam", level="WARNING") as log:
            frames = [f for f in folder]
        self.assertEqual(len(frames), 29)
        self.assertEqual(folder.skipped, 1)
        self.assertIn("frame 4 skipped", "\n".join(log.output))
        self.assertIn("skipped=1", repr(folder))
        self.assertIn("Frame(timestamp=", repr(frames[0]))
        shutil.rmtree(work)

    def test_one_pass(self):
        folder = amos_slam.SequenceFolder(SEQUENCE)
        self.assertEqual(len(folder), 30)
        self.assertEqual(sum(1 for _ in folder), 30)
        self.assertEqual(sum(1 for _ in folder), 0)


BAG_FROM_FOLDER = os.environ.get("AMOS_BAG_FROM_FOLDER", "")


@unittest.skipUnless(amos_slam.bags_available and BAG_FROM_FOLDER, "the module was built without the ROS part")
class Bags(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = pathlib.Path(tempfile.mkdtemp())
        cls.bag = cls.work / "seq.bag"
        subprocess.run([BAG_FROM_FOLDER, str(SEQUENCE), str(cls.bag), "--config", str(CONFIG)], check=True,
                       stdout=subprocess.DEVNULL)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work)

    def test_a_bag_reads_as_its_folder(self):
        folder = amos_slam.SequenceFolder(SEQUENCE)
        with amos_slam.SequenceFolder(self.bag) as bag:
            self.assertTrue(bag.is_bag)
            self.assertFalse(folder.is_bag)
            self.assertEqual(len(bag), len(folder))
            frames = list(bag)
            self.assertEqual(bag.skipped, 0)
            self.assertEqual(bag.ground_truth, [])  # no groundtruth.txt beside it, no topic asked for
        self.assertEqual([f.timestamp for f in frames], [folder.read(i).timestamp for i in range(len(folder))])
        first = folder.read(0)
        np.testing.assert_array_equal(frames[0].bgr, first.bgr)
        np.testing.assert_array_equal(frames[0].depth, first.depth)
        self.assertIn("seq.bag:/camera/rgb/image_color/", frames[0].rgb_file)
        with self.assertRaisesRegex(RuntimeError, "moved from"):
            len(bag)  # closed by the with block

    def test_topic_keywords(self):
        shutil.copy(SEQUENCE / "groundtruth.txt", self.work / "groundtruth.txt")
        try:
            bag = amos_slam.SequenceFolder(self.bag, rgb_topic="/camera/rgb/image_color")
            truth = amos_slam.SequenceFolder(SEQUENCE).ground_truth
            self.assertEqual([p.timestamp for p in bag.ground_truth], [p.timestamp for p in truth])
        finally:
            (self.work / "groundtruth.txt").unlink()
        with self.assertRaisesRegex(RuntimeError, f"bag '{re.escape(str(self.bag))}' has no colour topic '/nope'"):
            amos_slam.SequenceFolder(self.bag, rgb_topic="/nope", depth_topic="/camera/depth/image")
        with self.assertRaisesRegex(RuntimeError, "has no ground-truth topic '/tf'"):
            amos_slam.SequenceFolder(self.bag, groundtruth_topic="/tf")
        with self.assertRaisesRegex(RuntimeError, "topic '/camera/rgb/camera_info' holds sensor_msgs/CameraInfo"):
            amos_slam.SequenceFolder(self.bag, groundtruth_topic="/camera/rgb/camera_info")
        with self.assertRaises(TypeError):  # keywords only
            amos_slam.SequenceFolder(self.bag, "/camera/rgb/image_color")

    def test_a_folder_refuses_the_bag_keywords(self):
        with self.assertRaisesRegex(RuntimeError, "SequenceOptions::depth_topic '/d': only for a bag"):
            amos_slam.SequenceFolder(SEQUENCE, depth_topic="/d")


@unittest.skipIf(amos_slam.bags_available, "the module reads bags")
class NoBags(unittest.TestCase):
    def test_a_bag_is_an_error_naming_it(self):
        with self.assertRaisesRegex(RuntimeError, "'x.bag' is a ROS 1 bag, and this library was built without"):
            amos_slam.SequenceFolder("x.bag")


@unittest.skipUnless(amos_slam.dense_available, "the library was built without Open3D")
class Dense(unittest.TestCase):
    def test_dense_map_arrays_files_and_reprs(self):
        with geometry_slam(dense=True, overrides={"Dense.liveEvery": 1}) as slam:
            for i, result in enumerate(slam.track_frames(amos_slam.SequenceFolder(SEQUENCE))):
                if i == 10:
                    with self.assertRaisesRegex(RuntimeError, "after finish"):
                        slam.dense_map()
            snapshot = slam.dense_snapshot()
            live_grid = slam.dense_live_grid()
        m = slam.dense_map()
        if live_grid is not None:
            self.assertEqual(live_grid.cells.ndim, 2)
        self.assertRegex(repr(m), r"DenseMap\(mesh_vertices=\d+, cloud_points=\d+, grid=")
        n = m.mesh.vertices.shape[0]
        self.assertGreater(n, 1000)
        self.assertEqual(m.mesh.vertices.dtype, np.float64)
        self.assertEqual(m.mesh.triangles.dtype, np.uint32)
        self.assertEqual(m.mesh.triangles.shape[1], 3)
        self.assertLess(m.mesh.triangles.max(), n)
        self.assertEqual(m.mesh.colors.shape, (n, 3))
        self.assertEqual(m.mesh.colors.dtype, np.uint8)
        self.assertEqual(m.cloud.points.shape[1], 3)
        self.assertEqual(m.cloud.colors.shape, m.cloud.points.shape)
        self.assertIn("Mesh(vertices=", repr(m.mesh))
        self.assertIn("Cloud(points=", repr(m.cloud))
        if snapshot is not None:
            self.assertIn("DenseSnapshot(points=", repr(snapshot))
            self.assertGreater(snapshot.frames_fused, 0)
        work = pathlib.Path(tempfile.mkdtemp())
        m.write_mesh_ply(work / "mesh.ply")
        m.write_cloud_ply(str(work / "cloud.ply"))
        self.assertTrue((work / "mesh.ply").read_bytes().startswith(b"ply"))
        if m.grid is None:
            with self.assertRaisesRegex(RuntimeError, "no floor plan"):
                m.write_floor_plan(work / "occupancy")
        else:
            self.assertEqual(m.grid.cells.ndim, 2)
            self.assertEqual(m.grid.cells.dtype, np.uint8)
            self.assertIn("OccupancyGrid(rows=", repr(m.grid))
            m.write_floor_plan(work / "occupancy")
            self.assertTrue((work / "occupancy.pgm").exists() and (work / "occupancy.yaml").exists())
        shutil.rmtree(work)

    def test_dense_calls_need_dense(self):
        with geometry_slam() as slam:
            pass
        with self.assertRaisesRegex(RuntimeError, "Options::dense"):
            slam.dense_map()


if __name__ == "__main__":
    unittest.main()
