"""Ports pbrt_ext's fabric BxDF into a pbrt-derived renderer's source tree (scripts/port-pbrt-v4,
scripts/port-pbrt-v3). A port is three things:

- generated headers: pbrt_ext's own headers with their includes mapped to the target's. Either
  committed under port/<target>/, so that a reader sees what the port adds, and checked against
  pbrt_ext's (--check, the drift test); or, where they are pbrt_ext's headers unchanged but for
  their namespace, written only into the target;
- hand-written files under port/<target>/ (the glue, the material, the tests), copied as they are;
- edits of the target's files: text inserted at an anchor, each applied once.

Applying computes every new file first and writes nothing if any edit fails, so a tree is left
either ported or untouched. Applying again changes nothing.
"""

import argparse
import difflib
import hashlib
import os
import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


@dataclass
class Edit:
    """Inserts `text` before or after the unique `anchor` in `path`, or replaces the anchor by it.
    `applied` is a string present in the file once the edit is made."""
    path: str
    anchor: str
    text: str
    where: str  # "before", "after" or "replace"
    applied: str

    def apply(self, content):
        if self.applied in content:
            return content
        count = content.count(self.anchor)
        if count != 1:
            raise PortError(f"{self.path}: expected the text {self.anchor.strip()!r} once, "
                            f"found it {count} times")
        if self.where == "before":
            return content.replace(self.anchor, self.text + self.anchor)
        if self.where == "after":
            return content.replace(self.anchor, self.anchor + self.text)
        return content.replace(self.anchor, self.text)


@dataclass
class Port:
    name: str                 # "pbrt-v4"
    revision: str             # the target's commit the port was made for
    marker: str               # a file that every tree of the target has
    pinned: dict              # path -> sha256 of each edited file at `revision`
    generated: dict           # path in the target -> pbrt_ext header it is generated from
    committed: bool           # whether port/<name>/ holds the generated headers
    include_map: list         # (regex on an include line's path, replacement include line)
    edits: list = field(default_factory=list)
    substitutions: list = field(default_factory=list)  # (regex, replacement) on the other lines

    @property
    def files(self):
        return REPO / "port" / self.name

    def generate(self, source):
        """pbrt_ext's header with each `#include "pbrt_ext/..."` line mapped to the target's, and
        the port's substitutions (a namespace) made in the other lines."""
        out = [f"// Generated from {source} by scripts/port-{self.name} --regenerate: edit that "
               "file, not this one.\n"]
        for line in (REPO / source).read_text().splitlines(keepends=True):
            m = re.match(r'#include "(pbrt_ext/[^"]+)"', line)
            if m:
                line = self.map_include(m.group(1), source)
            else:
                for pattern, replacement in self.substitutions:
                    line = re.sub(pattern, replacement, line)
            out.append(line)
        return "".join(out)

    def map_include(self, path, source):
        for pattern, replacement in self.include_map:
            if re.fullmatch(pattern, path):
                return re.sub(pattern, replacement, path) + "\n"
        raise PortError(f"{source}: no mapping for #include \"{path}\" in scripts/port-{self.name}")

    def drift(self):
        """The committed generated files that differ from what pbrt_ext's headers generate now, as
        diffs (none when the port commits none: generating every one still checks its includes)."""
        diffs = []
        for target, source in self.generated.items():
            if not self.committed:
                self.generate(source)
                continue
            committed = self.files / target
            old = committed.read_text() if committed.exists() else ""
            new = self.generate(source)
            if old != new:
                diffs.append("".join(difflib.unified_diff(
                    old.splitlines(keepends=True), new.splitlines(keepends=True),
                    str(committed.relative_to(REPO)), f"generated from {source}")))
        return diffs

    def regenerate(self):
        if not self.committed:
            raise PortError(f"port/{self.name} holds no generated headers: they are written "
                            "into the tree when the port is applied")
        for target, source in self.generated.items():
            path = self.files / target
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(self.generate(source))
            print(f"wrote {path.relative_to(REPO)}")

    def copied_files(self):
        return sorted(p.relative_to(self.files) for p in self.files.rglob("*") if p.is_file())

    def apply(self, tree):
        tree = Path(tree)
        if not (tree / self.marker).is_file():
            raise PortError(f"{tree}: not a {self.name} source tree (no {self.marker})")
        diffs = self.drift()
        if diffs:
            raise PortError(f"port/{self.name} is out of date with pbrt_ext's headers; run "
                            f"scripts/port-{self.name} --regenerate\n" + "".join(diffs))
        self.report_revision(tree)

        changes = {str(rel): (self.files / rel).read_text() for rel in self.copied_files()}
        if not self.committed:
            changes.update({target: self.generate(source)
                            for target, source in self.generated.items()})
        for edit in self.edits:
            current = changes.get(edit.path)
            if current is None:
                current = (tree / edit.path).read_text()
            try:
                changes[edit.path] = edit.apply(current)
            except PortError as e:
                raise PortError(f"{e}\nThis port was made for {self.name} {self.revision}; "
                                f"{edit.path} in {tree} differs from it. Nothing was changed.")

        written = []
        for rel, content in changes.items():
            path = tree / rel
            if path.exists() and path.read_text() == content:
                continue
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(content)
            written.append(rel)
        if written:
            print(f"ported pbrt_ext's fabric BxDF into {tree}; changed:")
            for rel in written:
                print(f"  {rel}")
        else:
            print(f"nothing to change: {tree} already has the port")

    def report_revision(self, tree):
        """Says whether the tree is the revision the port was made for, judged by the files it edits
        (a tree from `git archive` has no history)."""
        if (tree / ".git").exists():
            head = subprocess.run(["git", "-C", str(tree), "rev-parse", "HEAD"],
                                  capture_output=True, text=True).stdout.strip()
            if head and not head.startswith(self.revision):
                print(f"note: {tree} is at {head[:12]}; the port was made for {self.revision}")
        pristine_edits = [e for e in self.edits if e.applied not in (tree / e.path).read_text()]
        for path in sorted({e.path for e in pristine_edits}):
            digest = hashlib.sha256((tree / path).read_bytes()).hexdigest()
            if digest != self.pinned[path]:
                print(f"note: {path} differs from {self.name} {self.revision}, for which the port "
                      "was made; trying the edits anyway")


class PortError(Exception):
    pass


def main(port):
    parser = argparse.ArgumentParser(
        prog=f"port-{port.name}",
        description=f"Ports pbrt_ext's fabric BxDF and material into a {port.name} source tree.")
    parser.add_argument("tree", nargs="?", help=f"the {port.name} source tree to change")
    parser.add_argument("--check", action="store_true",
                        help=f"exit 1 if port/{port.name}'s generated headers differ from what "
                             "pbrt_ext's headers generate (the drift test)")
    parser.add_argument("--regenerate", action="store_true",
                        help=f"rewrite port/{port.name}'s generated headers from pbrt_ext's")
    args = parser.parse_args()
    try:
        if args.check:
            diffs = port.drift()
            sys.stdout.write("".join(diffs))
            if diffs:
                print(f"port/{port.name} has drifted from pbrt_ext's headers: run "
                      f"scripts/port-{port.name} --regenerate", file=sys.stderr)
                return 1
            print(f"port/{port.name}: the generated headers match pbrt_ext's"
                  if port.committed else
                  f"port/{port.name}: every header it generates maps its includes")
            return 0
        if args.regenerate:
            port.regenerate()
            return 0
        if not args.tree:
            parser.error("give the source tree to port into")
        port.apply(args.tree)
        return 0
    except (PortError, OSError) as e:
        print(f"port-{port.name}: error: {e}", file=sys.stderr)
        return 1
