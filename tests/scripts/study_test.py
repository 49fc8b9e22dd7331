#!/usr/bin/python3
"""scripts/study and scripts/render-distributed on local Dask clusters they start (issue 21):
a tiny study gives every row once; a study stopped by Ctrl-C and run again renders only the
rest; a worker killed mid-study loses and duplicates nothing; a broken scene is recorded as
failed with pbrt_ext's message while the rest goes on; a distributed render equals one render.

Run by ctest with PBRT_EXT_CLI set to the pbrt_ext binary. Each study renders films of 32x24 or
64x48 pixels, seconds in all.
"""
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "scripts", "lib"))
import plotstyle  # noqa: E402  (after the path)
import studymodel  # noqa: E402
import studyreport  # noqa: E402
import studytasks  # noqa: E402

BINARY = os.environ.get("PBRT_EXT_CLI", os.path.join(REPO, "build", "release", "pbrt_ext", "cmd",
                                                     "pbrt_ext"))
STUDY = os.path.join(REPO, "scripts", "study")
SCENES = os.path.join(REPO, "scenes", "convergence")
TIMEOUT = 240  # seconds any one command may take here before the test fails


def study_text(scenes, spp, resolution=(32, 24)):
    """2 scenes x 2 strategies x 2 spp x 2 seeds = 16 configurations per 2 scenes."""
    return (f'binary = "{BINARY}"\nscenes = {scenes!r}\nstrategies = ["bsdf", "mis"]\n'
            f'spp = {spp!r}\nseeds = [0, 1]\nresolution = {list(resolution)!r}\n'
            '[reference]\nspp = 64\nslices = 4\n').replace("'", '"')


class StudyCase(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="pbrt_ext_study_test.")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def write_study(self, text, name="study.toml"):
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def run_study(self, path, *extra):
        return subprocess.run([STUDY, "run", path, "--workers", "2", *extra], capture_output=True,
                              text=True, timeout=TIMEOUT)

    def rows(self, path):
        database = os.path.splitext(path)[0] + ".study/results.sqlite"
        with sqlite3.connect(database) as connection:
            connection.row_factory = sqlite3.Row
            return [dict(r) for r in connection.execute("SELECT * FROM results")]

    def assert_every_row_once(self, path, count):
        rows = self.rows(path)
        keys = [(r["scene"], r["strategy"], r["spp"], r["seed"]) for r in rows]
        self.assertEqual(len(keys), count)
        self.assertEqual(len(set(keys)), count, "a configuration has two results")
        return rows

    def start_study(self, path):
        return subprocess.Popen([STUDY, "run", path, "--workers", "2"], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)

    def wait_for_rows(self, path, process, at_least):
        deadline = time.monotonic() + TIMEOUT
        while time.monotonic() < deadline and process.poll() is None:
            try:
                if len(self.rows(path)) >= at_least:
                    return
            except sqlite3.Error:
                pass  # not created yet
            time.sleep(0.05)
        self.fail(f"the study stored fewer than {at_least} results")

    def slow_study(self):
        """16 configurations of 0.1-0.7 s each: long enough to stop or hurt mid-way."""
        return self.write_study(study_text([f"{SCENES}/cylinder_r0.1.pbrt",
                                            f"{SCENES}/cornell_fabric.pbrt"], [32, 128], (64, 48)))


class Study(StudyCase):
    def test_tiny_study_gives_every_row_once(self):
        path = self.write_study(study_text([f"{SCENES}/cylinder_r0.1.pbrt",
                                            f"{SCENES}/cornell_fabric.pbrt"], [4, 16]))
        done = self.run_study(path)
        self.assertEqual(done.returncode, 0, done.stderr)
        rows = self.assert_every_row_once(path, 16)
        for r in rows:
            self.assertEqual(r["status"], "ok", r)
            self.assertGreater(r["relmse"], 0)
            self.assertGreater(r["wall_seconds"], r["seconds"])
            self.assertTrue(r["worker"] and r["binary_version"] and r["scene_hash"])
        # The two local workers both rendered.
        self.assertEqual(len({r["worker"] for r in rows}), 2)
        # MIS beats BSDF sampling on the small light's cylinder at every spp (relMSE 0.07-0.3
        # against 20-250 at these counts).
        by = {(r["scene"], r["strategy"], r["spp"], r["seed"]): r["relmse"] for r in rows}
        for spp in (4, 16):
            for seed in (0, 1):
                self.assertLess(by[("cylinder_r0.1", "mis", spp, seed)],
                                by[("cylinder_r0.1", "bsdf", spp, seed)])
        # Nothing left: a second run renders nothing and adds no row.
        again = self.run_study(path)
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("0 configurations to render, 16 stored", again.stderr)
        self.assert_every_row_once(path, 16)
        report = subprocess.run([STUDY, "report", path], capture_output=True, text=True,
                                timeout=TIMEOUT)
        self.assertEqual(report.returncode, 0, report.stderr)
        self.assertIn("### cylinder_r0.1", report.stdout)
        self.assertIn("No configuration failed.", report.stdout)

    def test_function_tables_join_the_study_and_its_report(self):
        path = self.write_study(
            f'binary = "{BINARY}"\nscenes = ["{SCENES}/cylinder_r0.1.pbrt"]\nspp = [4]\n'
            'samplers = ["independent", "sobol", "paddedsobol"]\nseeds = [0, 1]\nresolution = [16, 12]\n'
            '[reference]\nspp = 16\nslices = 2\n'
            '[functions]\nnames = ["step", "gaussian"]\nspp = 64\nresolution = [16, 16]\n')
        done = self.run_study(path)
        self.assertEqual(done.returncode, 0, done.stderr)
        # 3 samplers x 2 seeds renders, and 2 functions x 2 samplers (sobol is left out) x 2
        # seeds tables.
        self.assertIn("14 configurations to render, 0 stored", done.stderr)
        database = os.path.splitext(path)[0] + ".study/results.sqlite"
        with sqlite3.connect(database) as connection:
            tables = connection.execute("SELECT function, sampler, seed, status, rows FROM "
                                        "function_results").fetchall()
        self.assertEqual(len(tables), 8)
        self.assertEqual({t[1] for t in tables}, {"independent", "paddedsobol"})
        for function, sampler, seed, status, rows in tables:
            self.assertEqual(status, "ok", (function, sampler, seed))
            counts = [n for n, _ in json.loads(rows)]
            # paddedsobol writes rows at powers of two only (skipbad), independent at every n.
            self.assertEqual(counts, [1, 2, 4, 8, 16, 32, 64] if sampler == "paddedsobol"
                             else list(range(1, 65)))
        again = self.run_study(path)
        self.assertIn("0 configurations to render, 14 stored", again.stderr)
        report = subprocess.run([STUDY, "report", path], capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(report.returncode, 0, report.stderr)
        self.assertIn("### gaussian", report.stdout)
        self.assertIn("| paddedsobol | 64 |", report.stdout)
        self.assertIn("sobol is left out", report.stdout)
        self.assertTrue(os.path.exists(os.path.splitext(path)[0] + ".study/functions.png"))

    def test_interrupted_study_resumes_with_the_rest(self):
        path = self.slow_study()
        process = self.start_study(path)
        self.wait_for_rows(path, process, 3)
        process.send_signal(signal.SIGINT)
        output = process.communicate(timeout=TIMEOUT)[0]
        self.assertEqual(process.returncode, 130, output)
        first = {r["key"]: r for r in self.rows(path)}
        self.assertLess(len(first), 16, "the study finished before the interrupt")
        done = self.run_study(path)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn(f"{16 - len(first)} configurations to render, {len(first)} stored",
                      done.stderr)
        rows = self.assert_every_row_once(path, 16)
        # The first run's results are kept as they were.
        for r in rows:
            if r["key"] in first:
                self.assertEqual(r, first[r["key"]])

    def kill_worker_rendering(self, process, reference_slice):
        """SIGKILLs a worker of the study in the middle of a render, of a reference's slice
        (--samples) or of a configuration: the parent of such a running pbrt_ext."""
        deadline = time.monotonic() + TIMEOUT
        while time.monotonic() < deadline and process.poll() is None:
            for pid in os.listdir("/proc"):
                try:
                    with open(f"/proc/{pid}/cmdline", "rb") as f:
                        command = f.read().split(b"\0")
                    if (os.path.basename(command[0]) != b"pbrt_ext"
                            or (b"--samples" in command) != reference_slice):
                        continue
                    with open(f"/proc/{pid}/stat") as f:
                        parent = int(f.read().rsplit(")", 1)[1].split()[1])
                    with open(f"/proc/{parent}/stat") as f:
                        grandparent = int(f.read().rsplit(")", 1)[1].split()[1])
                except (OSError, ValueError, IndexError):
                    continue
                if grandparent == process.pid:  # the worker is a child of the study
                    os.kill(parent, signal.SIGKILL)
                    return
        self.fail("no worker caught rendering " + ("a slice" if reference_slice else
                                                   "a configuration"))

    def assert_killed_worker_lost_and_duplicated_nothing(self, path, process):
        output = process.communicate(timeout=TIMEOUT)[0]
        self.assertEqual(process.returncode, 0, output)
        rows = self.assert_every_row_once(path, 16)
        for r in rows:
            self.assertEqual(r["status"], "ok", r)

    def test_worker_killed_in_a_configuration_loses_and_duplicates_nothing(self):
        path = self.slow_study()
        process = self.start_study(path)
        self.wait_for_rows(path, process, 2)
        self.kill_worker_rendering(process, reference_slice=False)
        self.assert_killed_worker_lost_and_duplicated_nothing(path, process)

    def test_worker_killed_in_a_reference_slice_loses_and_duplicates_nothing(self):
        path = self.slow_study()
        process = self.start_study(path)
        self.kill_worker_rendering(process, reference_slice=True)
        self.assert_killed_worker_lost_and_duplicated_nothing(path, process)
        references = os.path.join(self.dir, "study.study", "references")
        self.assertEqual(sorted(f for f in os.listdir(references) if ".slice" not in f),
                         ["cornell_fabric.spp64.seed1000.exr", "cylinder_r0.1.spp64.seed1000.exr"])

    def test_broken_scene_is_recorded_as_failed_with_its_message(self):
        broken = os.path.join(self.dir, "broken.pbrt")
        with open(broken, "w") as f:
            f.write('Film "rgb"\nWorldBegin\nShape "teapot"\n')
        path = self.write_study(study_text([f"{SCENES}/cylinder_r0.1.pbrt", broken], [4, 16]))
        done = self.run_study(path)
        self.assertEqual(done.returncode, 1, done.stderr)
        self.assertIn("8 configurations failed", done.stderr)
        rows = self.assert_every_row_once(path, 16)
        for r in rows:
            if r["scene"] == "broken":
                self.assertEqual(r["status"], "failed")
                self.assertIn(f"{broken}:3:", r["message"])
                self.assertIn("teapot", r["message"])
            else:
                self.assertEqual(r["status"], "ok", r)
        report = subprocess.run([STUDY, "report", path], capture_output=True, text=True,
                                timeout=TIMEOUT)
        self.assertIn("## Failures (8)", report.stdout)
        self.assertIn("teapot", report.stdout)
        # Not retried: a second run renders nothing more.
        again = self.run_study(path)
        self.assertIn("0 configurations to render, 16 stored", again.stderr)


class StudyFileErrors(StudyCase):
    def test_bad_study_files_are_refused_before_anything_runs(self):
        scene = f'scenes = ["{SCENES}/cylinder_r0.1.pbrt"]\nspp = [4]\n'
        cases = {
            'scenes = ["missing.pbrt"]\nspp = [4]\n': 'scene "missing.pbrt" not found',
            scene + 'strategy = ["mis"]\n': 'unknown key "strategy"',
            scene + 'seeds = [0, "one"]\n': '"seeds" must be a list of ints',
            scene + 'threads = 0\n': '"threads" must be a positive integer',
            scene + 'resolution = [32]\n': '"resolution" must be two positive integers',
            scene + '[reference]\nslices = -2\n': '"reference.slices" must be a positive integer',
            scene + '[reference]\nseed = 0\n': "the reference's seed 0 is one of",
            scene + '[functions]\nnames = ["sine"]\n': '"functions.names" must name some of',
            scene + '[functions]\nnames = ["step"]\n': '[functions] needs "samplers"',
            scene + 'samplers = ["halton"]\n[functions]\nnames = ["step"]\nspp = 0\n':
                '"functions.spp" must be a positive integer',
            'scenes = [\n': "error: ",
        }
        for text, message in cases.items():
            path = self.write_study(text, "bad.toml")
            done = self.run_study(path)
            self.assertEqual(done.returncode, 2, text)
            self.assertIn(f"{path}: error: ", done.stderr)
            self.assertIn(message, done.stderr, text)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "bad.study")), text)


class MakespanModel(unittest.TestCase):
    def test_list_scheduling_of_a_reference_and_its_configurations(self):
        # Two 1 s slices, their 0.1 s merge, then four 1 s configurations that wait for it.
        tasks = [("s0", 1, 10, []), ("s1", 1, 10, []), ("merge", 0.1, 10, ["s0", "s1"])]
        tasks += [(f"c{i}", 1, 0, ["merge"]) for i in range(4)]
        self.assertAlmostEqual(studymodel.predict(tasks, 1), 6.1)
        # Both slices at once; one worker merges while the other waits; then 2 + 2 configurations.
        self.assertAlmostEqual(studymodel.predict(tasks, 2), 3.1)
        # More workers than configurations: the critical path, 1 + 0.1 + 1.
        self.assertAlmostEqual(studymodel.predict(tasks, 8), 2.1)

    def test_priority_puts_references_first(self):
        # A long configuration of another scene, submitted first, waits behind the reference.
        tasks = [("other", 5, 0, []), ("s0", 1, 10, []), ("c", 1, 0, ["s0"])]
        self.assertAlmostEqual(studymodel.predict(tasks, 1), 7)
        self.assertAlmostEqual(studymodel.predict(tasks, 2), 5)


    def test_replay_starts_each_task_after_those_it_waits_for(self):
        # The graph above, each task sleeping its time x 0.2, on 4 local workers: started at
        # once, the tasks would take 0.2 s; the critical path (slice, merge, configuration)
        # takes 0.42 s whatever Dask adds.
        tasks = [("s0", 1, 10, []), ("s1", 1, 10, []), ("merge", 0.1, 10, ["s0", "s1"])]
        tasks += [(f"c{i}", 1, 0, ["merge"]) for i in range(4)]
        self.assertGreaterEqual(studymodel.replay(tasks, 4, 0.2), 0.42)

REPORT_MD = """# Study tiny

### cylinder_r0.1 (baseline: mis / best)

| series | relMSE 4 | relMSE 16 | c | c / baseline | efficiency / baseline | eff. 4 / baseline | eff. 16 / baseline |
|---|---|---|---|---|---|---|---|
| bsdf / best | 53.1 | 13.5 | 216 | 568 | 0.00263 | 0.00 | 0.00 |
| mis / best | 0.107 | 0.0243 | 0.38 | 1 | 1 | 1.00 | 1.00 |
| mis / paper | 0.0979 | – | 0.388 | 1.02 | 1.3 | 1.13 | – |

## Cost per task

| not | a scene table |
|---|---|
"""


class ReportPlots(unittest.TestCase):
    """The plots' styles and a report.md read back (scripts/study replot); no renders."""

    def test_every_series_has_its_own_colour_and_marker(self):
        grouped = [(a, b) for a in ("bsdf", "light", "mis")
                   for b in ("uniform", "cosine", "paper", "best")]
        for keys in (grouped, [f"s{i}" for i in range(7)], [f"s{i}" for i in range(25)],
                     [("a", f"x{i}", "b") for i in range(5)]):
            styles = plotstyle.series_styles(keys)
            self.assertEqual(len({styles[k]["color"] for k in keys}), len(keys), keys)
            self.assertEqual(len({(styles[k]["color"], styles[k]["marker"]) for k in keys}),
                             len(keys), keys)
        # Grouped: one marker per sampler, one line style per strategy.
        styles = plotstyle.series_styles(grouped)
        self.assertEqual(styles[("bsdf", "paper")]["marker"], styles[("mis", "paper")]["marker"])
        self.assertNotEqual(styles[("bsdf", "paper")]["linestyle"],
                            styles[("mis", "paper")]["linestyle"])

    def test_log_limits_hold_every_value(self):
        low, high = plotstyle.log_limits([0.00075, 1.06, float("nan"), 0, None])
        self.assertLess(low, 0.00075)
        self.assertGreater(high, 1.06)
        self.assertIsNone(plotstyle.log_limits([0, float("nan")]))

    def test_replot_reads_the_scene_tables_of_a_report(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "tiny.md")
            with open(path, "w") as f:
                f.write(REPORT_MD)
            series, ratios, baselines = studyreport.read_report(path)
            self.assertEqual(list(series), ["cylinder_r0.1"])
            self.assertEqual(series["cylinder_r0.1"][("bsdf", "best")],
                             [(4, None, 53.1), (16, None, 13.5)])
            self.assertEqual(series["cylinder_r0.1"][("mis", "paper")], [(4, None, 0.0979)])
            self.assertEqual(ratios["cylinder_r0.1"][("mis", "paper")], 1.3)
            self.assertEqual(baselines["cylinder_r0.1"], ("mis", "best"))
            done = subprocess.run([STUDY, "replot", path, "--out", os.path.join(folder, "out")],
                                  capture_output=True, text=True, timeout=TIMEOUT)
            self.assertEqual(done.returncode, 0, done.stderr)
            for name in ("relmse.png", "efficiency.png"):
                self.assertGreater(os.path.getsize(os.path.join(folder, "out", name)), 1000)


class RenderDistributed(StudyCase):
    def test_parts_merge_into_the_single_render(self):
        scene = os.path.join(REPO, "scenes", "cornell-box-fabric.pbrt")
        common = ["--spp", "12", "--resolution", "40,30", "--seed", "5"]
        single = os.path.join(self.dir, "single.exr")
        subprocess.run([BINARY, "--quiet", *common, "--outfile", single, scene], check=True,
                       timeout=TIMEOUT)
        merged = os.path.join(self.dir, "merged.exr")
        done = subprocess.run([os.path.join(REPO, "scripts", "render-distributed"), scene,
                               "--parts", "3", "--workers", "2", "--outfile", merged,
                               "--binary", BINARY, "--", *common],
                              capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(done.returncode, 0, done.stderr)
        a, b = studytasks.read_rgb(single), studytasks.read_rgb(merged)
        relative = abs(a - b) / (abs(a) + 1e-3)
        self.assertLessEqual(float(relative.max()), 1e-5)
        self.assertEqual(sorted(os.listdir(self.dir)), ["merged.exr", "single.exr"])

    def test_a_failed_part_writes_nothing(self):
        merged = os.path.join(self.dir, "merged.exr")
        done = subprocess.run([os.path.join(REPO, "scripts", "render-distributed"),
                               os.path.join(SCENES, "cylinder_r0.1.pbrt"), "--parts", "2",
                               "--workers", "2", "--outfile", merged, "--binary", BINARY, "--",
                               "--spp", "4", "--integrator", "nonsense"],
                              capture_output=True, text=True, timeout=TIMEOUT)
        self.assertEqual(done.returncode, 1, done.stderr)
        self.assertIn("nothing written", done.stderr)
        self.assertEqual(os.listdir(self.dir), [])

    def test_merge_refuses_overlapping_slices_and_writes_nothing(self):
        scene = os.path.join(SCENES, "cylinder_r0.1.pbrt")
        part = os.path.join(self.dir, "part.exr")
        subprocess.run([BINARY, "--quiet", "--spp", "4", "--resolution", "16,12", "--samples",
                        "0:3", "--outfile", part, scene], check=True, timeout=TIMEOUT)
        out = os.path.join(self.dir, "out.exr")
        done = subprocess.run([BINARY, "merge", out, part, part], capture_output=True, text=True,
                              timeout=TIMEOUT)
        self.assertEqual(done.returncode, 1)
        self.assertIn("overlap", done.stderr)
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
