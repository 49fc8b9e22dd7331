#!/usr/bin/env python3
"""scripts/check-include-rules on small trees under docs/architecture.md's real table: it passes the
includes the table allows, and fails, naming file:line, on each kind of wrong include the table
exists to stop (an integrator included below integrators/, scene text read outside scene/, a
BxDF reaching past util/), and on a folder that no row covers."""
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "check-include-rules"


class IncludeRules(unittest.TestCase):
    def setUp(self):
        self.root = Path(tempfile.mkdtemp(prefix="include_rules_"))
        (self.root / "docs").mkdir()
        shutil.copy(REPO / "docs" / "architecture.md", self.root / "docs")

    def tearDown(self):
        shutil.rmtree(self.root)

    def write(self, path, *includes):
        file = self.root / "pbrt_ext" / path
        file.parent.mkdir(parents=True, exist_ok=True)
        file.write_text("".join(f'#include "pbrt_ext/{i}"\n' for i in includes) + "int x;\n")

    def check(self):
        run = subprocess.run([sys.executable, str(SCRIPT), "--root", str(self.root)],
                             capture_output=True, text=True)
        return run.returncode, run.stdout

    def test_allowed_includes_pass(self):
        self.write("film/film.cpp", "film/film.h", "spectra/spectrum.h", "util/math.h", "pbrt.h")
        self.write("integrators/path.cpp", "scene.h", "film/film.h", "integrators/path.h")
        self.write("render.cpp", "integrators/path.h", "scene.h")
        self.write("cmd/pbrt_ext.cpp", "scene/sceneloader.h", "integrators/path.h")
        code, out = self.check()
        self.assertEqual(code, 0, out)
        self.assertIn("every include", out)

    def test_an_integrator_below_integrators_fails(self):
        self.write("film/film.cpp", "film/film.h", "integrators/path.h")
        code, out = self.check()
        self.assertEqual(code, 1)
        self.assertIn("pbrt_ext/film/film.cpp:2: includes pbrt_ext/integrators/path.h", out)

    def test_scene_text_outside_scene_fails(self):
        self.write("lights/lights.cpp", "scene/paramdict.h")
        self.write("integrators/bdpt.cpp", "scene/parser.h")
        code, out = self.check()
        self.assertEqual(code, 1)
        self.assertIn("pbrt_ext/lights/lights.cpp:1: includes pbrt_ext/scene/paramdict.h", out)
        self.assertIn("pbrt_ext/integrators/bdpt.cpp:1: includes pbrt_ext/scene/parser.h", out)

    def test_bxdfs_and_base_include_only_util(self):
        self.write("bxdfs/fabric.h", "util/math.h", "base/bxdf.h", "spectra/spectrum.h")
        self.write("base/bxdf.h", "util/math.h", "bxdfs/fabric.h")
        code, out = self.check()
        self.assertEqual(code, 1)
        self.assertIn("pbrt_ext/bxdfs/fabric.h:3: includes pbrt_ext/spectra/spectrum.h", out)
        self.assertIn("pbrt_ext/base/bxdf.h:2: includes pbrt_ext/bxdfs/fabric.h", out)
        self.assertIn("2 include(s) break", out)

    def test_a_folder_without_a_row_fails(self):
        self.write("guiding/sdtree.h", "util/math.h")
        code, out = self.check()
        self.assertEqual(code, 1)
        self.assertIn("no row of docs/architecture.md covers guiding/", out)


if __name__ == "__main__":
    unittest.main()
