"""A study file (TOML): which scenes to render in which configurations, and their reference.

    name = "fabric-samplers"        # default: the file's name without .toml
    scenes = ["cylinder_r0.1.pbrt", "cornell_fabric.pbrt"]   # relative to the study file
    strategies = ["bsdf", "light", "mis"]              # pbrt_ext --strategy
    fabric_samplers = ["uniform", "paper", "best"]     # --fabric-sampler
    light_samplers = ["bvh", "power"]                  # --light-sampler
    samplers = ["independent", "zsobol"]               # --sampler
    integrators = ["path", "bdpt"]                     # --integrator
    spp = [4, 16, 64]                                  # --spp (required)
    seeds = [0, 1]                                     # --seed (default [0])
    resolution = [128, 96]          # --resolution for every render (default: each scene's)
    threads = 1                     # --nthreads per render (default 1)
    timeout = 600                   # seconds a render may take before it counts as failed
    binary = "../build/release/pbrt_ext/cmd/pbrt_ext"  # default: this checkout's release build

    [reference]                     # one per scene, rendered first, split into slices
    spp = 4096
    seed = 1000                     # must not be one of seeds
    slices = 8
    integrator = { caustic_fabric = "bdpt" }   # per scene name (default: the scene's)

    [report]
    baseline = { fabric_sampler = "best", strategy = "mis" }   # what ratios are relative to

    [functions]                     # pbrt-v4's function integrator, with each of "samplers"
    names = ["step", "gaussian"]    # its test functions (step, diagonal, disk, checkerboard,
                                    # rotatedcheckerboard, gaussian)
    spp = 1024                      # samples per pixel: the last row of each table
    resolution = [64, 64]           # pixels, each one estimate (default 64 x 64)

A list left out (or empty) is the scene's own choice. Every combination of the lists is one
configuration. A reference uses MIS, the best fabric sampler and the scene's other choices.
With [functions], every combination of its names, "samplers" and the seeds is also run by the
function integrator (no scene, no reference): its table of mean squared errors against the
sample count joins the report.
"""
import hashlib
import itertools
import json
import os
import re
import tomllib
from dataclasses import dataclass, field

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_BINARY = os.path.join(REPO, "build", "release", "pbrt_ext", "cmd", "pbrt_ext")

# Study-file key -> (configuration field, pbrt_ext option).
DIMENSIONS = {
    "strategies": ("strategy", "--strategy"),
    "fabric_samplers": ("fabric_sampler", "--fabric-sampler"),
    "light_samplers": ("light_sampler", "--light-sampler"),
    "samplers": ("sampler", "--sampler"),
    "integrators": ("integrator", "--integrator"),
}
FIELDS = ["scene", *[f for f, _ in DIMENSIONS.values()], "spp", "seed"]


class StudyError(Exception):
    """A study file that cannot be run: the message names the file."""


@dataclass
class Scene:
    name: str   # the file name without .pbrt
    path: str   # absolute
    hash: str   # of the file and the files it includes


@dataclass
class Study:
    path: str
    name: str
    binary: str
    scenes: list
    choices: dict            # configuration field -> list of values ([None]: the scene's)
    spp: list
    seeds: list
    resolution: list = None
    threads: int = 1
    timeout: float = 600
    reference_spp: int = 4096
    reference_seed: int = 1000
    reference_slices: int = 8
    reference_integrator: dict = field(default_factory=dict)
    baseline: dict = field(default_factory=dict)
    functions: list = field(default_factory=list)   # [functions] names
    function_spp: int = 1024
    function_resolution: list = field(default_factory=lambda: [64, 64])

    @property
    def folder(self):
        """Beside the study file: the database, the references, the report."""
        return os.path.splitext(self.path)[0] + ".study"

    @property
    def database(self):
        return os.path.join(self.folder, "results.sqlite")

    def common_args(self):
        args = ["--nthreads", str(self.threads)]
        if self.resolution:
            args += ["--resolution", ",".join(map(str, self.resolution))]
        return args

    def configurations(self):
        """Every configuration: a dict of FIELDS, None where the scene chooses."""
        for scene in self.scenes:
            dims = [self.choices[f] for f, _ in DIMENSIONS.values()]
            for values in itertools.product(*dims, self.spp, self.seeds):
                yield dict(zip(FIELDS, [scene.name, *values]))

    def configuration_key(self, config):
        """What identifies a result: the configuration and what else decides its numbers."""
        return json.dumps({**config, "resolution": self.resolution, "threads": self.threads,
                           "reference": [self.reference_spp, self.reference_seed]},
                          sort_keys=True)

    def render_args(self, config):
        args = ["--spp", str(config["spp"]), "--seed", str(config["seed"]), *self.common_args()]
        for f, option in DIMENSIONS.values():
            if config[f] is not None:
                args += [option, str(config[f])]
        return args

    def reference_args(self, scene, first, last):
        args = ["--spp", str(self.reference_spp), "--seed", str(self.reference_seed),
                *self.common_args(), "--strategy", "mis", "--fabric-sampler", "best",
                "--samples", f"{first}:{last}"]
        if scene.name in self.reference_integrator:
            args += ["--integrator", self.reference_integrator[scene.name]]
        return args

    def function_samplers(self):
        """The samplers the function integrator runs: not "sobol", whose pixel samples are one
        sequence over the image (paddedsobol is the per-pixel one), as pbrt-v4 refuses it."""
        return [s for s in self.choices["sampler"] if s != "sobol"]

    def function_configurations(self):
        """Every (function, sampler, seed) of [functions]: dicts with spp."""
        for function, sampler, seed in itertools.product(self.functions, self.function_samplers(),
                                                        self.seeds):
            yield {"function": function, "sampler": sampler, "spp": self.function_spp, "seed": seed}

    def function_key(self, config):
        return json.dumps({**config, "resolution": self.function_resolution}, sort_keys=True)

    def function_scene(self, config):
        """The scene file's text: the function integrator alone (the sampler comes from args)."""
        x, y = self.function_resolution
        return (f'Film "rgb" "integer xresolution" {x} "integer yresolution" {y}\n'
                f'Integrator "function" "string function" "{config["function"]}"\n'
                'Camera "perspective"\nWorldBegin\n')

    def function_args(self, config):
        return ["--sampler", config["sampler"], "--seed", str(config["seed"]), "--spp",
                str(config["spp"]), "--nthreads", str(self.threads)]

    def reference_slices_of(self):
        """The sample ranges of the reference's slices: as equal as the count allows."""
        k = max(1, min(self.reference_slices, self.reference_spp))
        bounds = [self.reference_spp * i // k for i in range(k + 1)]
        return list(zip(bounds[:-1], bounds[1:]))

    def reference_path(self, scene):
        return os.path.join(self.folder, "references",
                            f"{scene.name}.spp{self.reference_spp}.seed{self.reference_seed}.exr")


def scene_hash(path, seen=None):
    """SHA-256 (16 hex digits) of the scene file and, recursively, the files it Includes or
    Imports (named relative to the main file's folder, as pbrt-v4 resolves them)."""
    seen = seen if seen is not None else set()
    digest = hashlib.sha256()
    root = os.path.dirname(path)

    def add(file):
        if file in seen or not os.path.isfile(file):
            return
        seen.add(file)
        with open(file, "rb") as f:
            text = f.read()
        digest.update(text)
        for name in re.findall(rb'^\s*(?:Include|Import)\s+"([^"]+)"', text, re.MULTILINE):
            add(os.path.join(root, name.decode()))

    add(path)
    return digest.hexdigest()[:16]


def _list(data, key, path, kind):
    value = data.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, kind) for v in value):
        raise StudyError(f"{path}: error: \"{key}\" must be a list of {kind.__name__}s")
    return value


def _positive(table, key, path, kind, default, where=""):
    """table[key] (default when absent) if it is a positive number of kind."""
    value = table.get(key, default)
    if isinstance(value, bool) or not isinstance(value, kind) or value <= 0:
        raise StudyError(f"{path}: error: \"{where}{key}\" must be a positive "
                         f"{'integer' if kind is int else 'number'}, not {value!r}")
    return value


TEST_FUNCTIONS = {"step", "diagonal", "disk", "checkerboard", "rotatedcheckerboard", "gaussian"}


def _load_functions(table, study, path):
    """[functions] into the study; StudyError for what the function integrator cannot run."""
    if not table:
        return
    unknown = sorted(set(table) - {"names", "spp", "resolution"})
    if unknown:
        raise StudyError(f"{path}: error: unknown key \"functions.{unknown[0]}\"; expected names, "
                         "spp or resolution")
    study.functions = _list(table, "names", path, str)
    bad = [n for n in study.functions if n not in TEST_FUNCTIONS]
    if bad or not study.functions:
        raise StudyError(f"{path}: error: \"functions.names\" must name some of "
                         f"{', '.join(sorted(TEST_FUNCTIONS))}" + (f", not \"{bad[0]}\"" if bad else ""))
    if study.choices["sampler"] == [None]:
        raise StudyError(f"{path}: error: [functions] needs \"samplers\" to compare")
    study.function_spp = _positive(table, "spp", path, int, 1024, "functions.")
    resolution = table.get("resolution", [64, 64])
    if not isinstance(resolution, list) or len(resolution) != 2 or not all(
            isinstance(v, int) and not isinstance(v, bool) and v > 0 for v in resolution):
        raise StudyError(f"{path}: error: \"functions.resolution\" must be two positive integers")
    study.function_resolution = resolution


def load(path):
    """The study of the file; raises StudyError for anything missing or misspelt."""
    path = os.path.abspath(path)
    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise StudyError(f"{path}: error: {e}") from e
    known = {"name", "scenes", "spp", "seeds", "resolution", "threads", "timeout", "binary",
             "reference", "report", "functions", *DIMENSIONS}
    unknown = sorted(set(data) - known)
    if unknown:
        raise StudyError(f"{path}: error: unknown key \"{unknown[0]}\"; expected one of "
                         + ", ".join(sorted(known)))
    folder = os.path.dirname(path)
    scenes = []
    for name in _list(data, "scenes", path, str):
        scene_path = os.path.normpath(os.path.join(folder, name))
        if not os.path.isfile(scene_path):
            raise StudyError(f"{path}: error: scene \"{name}\" not found ({scene_path})")
        stem = os.path.splitext(os.path.basename(scene_path))[0]
        scenes.append(Scene(stem, scene_path, scene_hash(scene_path)))
    spp = _list(data, "spp", path, int)
    if not scenes or not spp:
        raise StudyError(f"{path}: error: \"scenes\" and \"spp\" must name at least one each")
    if len({s.name for s in scenes}) != len(scenes):
        raise StudyError(f"{path}: error: two scenes share a file name")
    reference = data.get("reference", {})
    resolution = data.get("resolution")
    if resolution is not None and (not isinstance(resolution, list) or len(resolution) != 2 or not all(
            isinstance(v, int) and not isinstance(v, bool) and v > 0 for v in resolution)):
        raise StudyError(f"{path}: error: \"resolution\" must be two positive integers, not "
                         f"{resolution!r}")
    study = Study(
        path=path, name=data.get("name", os.path.splitext(os.path.basename(path))[0]),
        binary=os.path.normpath(os.path.join(folder, data["binary"])) if "binary" in data
        else DEFAULT_BINARY,
        scenes=scenes,
        choices={f: _list(data, key, path, str) or [None] for key, (f, _) in DIMENSIONS.items()},
        spp=spp, seeds=_list(data, "seeds", path, int) or [0], resolution=resolution,
        threads=_positive(data, "threads", path, int, 1),
        timeout=_positive(data, "timeout", path, (int, float), 600),
        reference_spp=_positive(reference, "spp", path, int, 4096, "reference."),
        reference_seed=reference.get("seed", 1000),
        reference_slices=_positive(reference, "slices", path, int, 8, "reference."),
        reference_integrator=reference.get("integrator", {}),
        baseline=data.get("report", {}).get("baseline", {}))
    _load_functions(data.get("functions", {}), study, path)
    if study.reference_seed in study.seeds:
        raise StudyError(f"{path}: error: the reference's seed {study.reference_seed} is one of "
                         "\"seeds\": a configuration would share its samples")
    if not os.access(study.binary, os.X_OK):
        raise StudyError(f"{path}: error: no pbrt_ext at {study.binary} (build it: scripts/setup)")
    return study
