"""The port scripts' behaviour on stand-in source trees (CI has no pbrt-v4 or pbrt-v3 source): each
stand-in file holds only the text its edits anchor on. Checks that a port adds its files and makes
every edit, that applying it again changes nothing, and that a tree missing an anchor is refused
with nothing written.

    python3 tests/port/port_test.py
"""
import contextlib
import importlib.machinery
import importlib.util
import io
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts" / "lib"))
from port import PortError  # noqa: E402


def load_port(name):
    loader = importlib.machinery.SourceFileLoader(name, str(REPO / "scripts" / name))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(name, loader))
    loader.exec_module(module)
    return module.PORT


def stand_in_tree(port, root):
    """A tree whose edited files hold only their anchors, one after the other."""
    files = {port.marker: ""}
    for edit in port.edits:
        files[edit.path] = files.get(edit.path, "") + edit.anchor + "\n"
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def snapshot(root):
    return {p.relative_to(root): p.read_bytes() for p in root.rglob("*") if p.is_file()}


def quietly(function, *args):
    with contextlib.redirect_stdout(io.StringIO()) as out:
        function(*args)
    return out.getvalue()


class PortTest(unittest.TestCase):
    def check(self, name):
        port = load_port(name)
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            stand_in_tree(port, root)
            quietly(port.apply, root)
            for rel in port.copied_files():
                self.assertTrue((root / rel).is_file(), rel)
            for target in port.generated:
                self.assertTrue((root / target).is_file(), target)
            for edit in port.edits:
                self.assertIn(edit.applied, (root / edit.path).read_text(), edit.path)

            before = snapshot(root)
            self.assertIn("nothing to change", quietly(port.apply, root))
            self.assertEqual(snapshot(root), before)

    def check_refuses_a_missing_anchor(self, name):
        port = load_port(name)
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            stand_in_tree(port, root)
            last = port.edits[-1]
            path = root / last.path
            path.write_text(path.read_text().replace(last.anchor, ""))
            before = snapshot(root)
            with self.assertRaisesRegex(PortError, "Nothing was changed"):
                quietly(port.apply, root)
            self.assertEqual(snapshot(root), before)

    def test_pbrt_v4(self):
        self.check("port-pbrt-v4")

    def test_pbrt_v3(self):
        self.check("port-pbrt-v3")

    def test_pbrt_v4_refuses_a_missing_anchor(self):
        self.check_refuses_a_missing_anchor("port-pbrt-v4")

    def test_pbrt_v3_refuses_a_missing_anchor(self):
        self.check_refuses_a_missing_anchor("port-pbrt-v3")


if __name__ == "__main__":
    unittest.main()
