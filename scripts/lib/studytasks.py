"""What a Dask worker runs for scripts/study and scripts/render-distributed: pbrt_ext as a
subprocess (one render, one slice, one merge or one function integrator's error table), timed,
and for a study's configuration its relMSE against the reference.

Self-contained (the standard library, NumPy and OpenImageIO): the client ships this file to
every worker (Client.upload_file), so a worker needs no checkout, only the binary, the scenes and
the study folder at the same paths (docs/distributed.md).

A render that fails returns its failure (status "failed" and pbrt_ext's message) instead of
raising: Dask would retry a raised task on another worker, and a broken scene fails everywhere.
A worker that dies mid-task is Dask's to reschedule.
"""
import hashlib
import os
import socket
import subprocess
import tempfile
import time

# Keeps the relative error of near-black pixels finite without letting them dominate (as
# benchmarks/convergence_bench.cpp).
RELMSE_EPSILON = 1e-2
_binary_versions = {}


def binary_version(binary):
    """The first 16 hex digits of the binary's SHA-256 (cached per path and modification time)."""
    key = (binary, os.stat(binary).st_mtime_ns)
    if key not in _binary_versions:
        with open(binary, "rb") as f:
            _binary_versions[key] = hashlib.sha256(f.read()).hexdigest()[:16]
    return _binary_versions[key]


def worker_name():
    """This worker: its host and process."""
    return f"{socket.gethostname()}:{os.getpid()}"


def read_rgb(path):
    """The R, G, B channels of an image as a float array (height, width, 3)."""
    import numpy as np
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    if image is None:
        raise RuntimeError(f"{path}: cannot read: {oiio.geterror()}")
    try:
        names = list(image.spec().channelnames)
        pixels = image.read_image(oiio.FLOAT)
    finally:
        image.close()
    if pixels is None or not all(c in names for c in "RGB"):
        raise RuntimeError(f"{path}: no R, G, B channels")
    return np.asarray(pixels)[:, :, [names.index(c) for c in "RGB"]]


def read_render_seconds(path):
    """The render's own time (scene loading excluded), from the EXR's renderTimeSeconds."""
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(path)
    try:
        return float(image.spec().getattribute("renderTimeSeconds"))
    finally:
        image.close()


def relmse(image, reference):
    """The mean over pixels and channels of (x - r)^2 / (r^2 + 1e-2)."""
    if image.shape != reference.shape:
        raise RuntimeError(f"the image is {image.shape[1]}x{image.shape[0]}, the reference "
                           f"{reference.shape[1]}x{reference.shape[0]}")
    d = image.astype("float64") - reference
    return float((d * d / (reference.astype("float64") ** 2 + RELMSE_EPSILON)).mean())


def _error_message(stderr, returncode):
    """pbrt_ext's error lines, or how the process ended."""
    lines = [line for line in stderr.splitlines() if "error" in line or "Error" in line]
    text = "\n".join(lines[-5:]) if lines else "\n".join(stderr.splitlines()[-5:])
    if returncode < 0:
        text = (text + "\n" if text else "") + f"killed by signal {-returncode}"
    return text or f"exit status {returncode}"


def run_pbrt_ext(binary, args, timeout):
    """Runs pbrt_ext with args; {"status", "message", "wall_seconds"}."""
    start = time.perf_counter()
    try:
        done = subprocess.run([binary, *args], capture_output=True, text=True,
                              timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "failed", "message": f"time limit of {timeout} s exceeded",
                "wall_seconds": time.perf_counter() - start}
    wall = time.perf_counter() - start
    if done.returncode != 0:
        return {"status": "failed", "message": _error_message(done.stderr, done.returncode),
                "wall_seconds": wall}
    return {"status": "ok", "message": "", "wall_seconds": wall}


def render_to(job, outfile):
    """Renders job (binary, scene, args, timeout) into outfile; the run_pbrt_ext record with
    the render's own seconds, the worker and the binary's version."""
    record = run_pbrt_ext(job["binary"], ["--quiet", *job["args"], "--outfile", outfile, job["scene"]],
                          job["timeout"])
    record["worker"] = worker_name()
    record["binary_version"] = binary_version(job["binary"])
    record["seconds"] = read_render_seconds(outfile) if record["status"] == "ok" else None
    return record


def render_configuration(job, reference):
    """One configuration of a study: rendered into a temporary file, compared with the
    reference (its path), then deleted."""
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="pbrt_ext_study_") as folder:
        outfile = os.path.join(folder, "render.exr")
        record = render_to(job, outfile)
        record["relmse"] = None
        if record["status"] == "ok":
            try:
                record["relmse"] = relmse(read_rgb(outfile), read_rgb(reference))
            except RuntimeError as e:
                record.update(status="failed", message=str(e))
    record["wall_seconds"] = time.perf_counter() - start  # reading the reference included
    return record


def function_table(binary, scene_text, args, timeout):
    """pbrt_ext's function integrator on scene_text (a scene of the Integrator "function"
    alone) with args (--sampler, --seed, --spp): {"status", "message", "wall_seconds", "rows":
    [[n, mse], ...], "worker", "binary_version"}."""
    with tempfile.TemporaryDirectory(prefix="pbrt_ext_study_") as folder:
        scene, table = os.path.join(folder, "function.pbrt"), os.path.join(folder, "mse.txt")
        with open(scene, "w") as f:
            f.write(scene_text)
        record = run_pbrt_ext(binary, ["--quiet", *args, "--outfile", table, scene], timeout)
        record["rows"] = None
        if record["status"] == "ok":
            with open(table) as f:
                record["rows"] = [[int(n), float(mse)] for n, mse in (line.split() for line in f)]
    record["worker"] = worker_name()
    record["binary_version"] = binary_version(binary)
    return record


def render_slice(job, outfile):
    """One slice (job["args"] holds --samples A:B), written to outfile atomically by pbrt_ext.
    An existing outfile is a slice an earlier run finished: kept."""
    if os.path.exists(outfile):
        return {"status": "ok", "message": "", "wall_seconds": 0.0, "seconds": 0.0,
                "worker": worker_name(), "binary_version": binary_version(job["binary"]),
                "reused": True}
    return render_to(job, outfile)


def merge_slices(binary, outfile, slice_files, timeout):
    """pbrt_ext merge of the slices into outfile, then the slices removed; the run_pbrt_ext
    record. Run again after its worker died, it keeps an outfile whose slices are already
    being removed: pbrt_ext writes the outfile atomically, and removes nothing before."""
    merged_before = os.path.exists(outfile) and not all(os.path.exists(f) for f in slice_files)
    record = {"status": "ok", "message": "", "wall_seconds": 0.0}
    if not merged_before:
        record = run_pbrt_ext(binary, ["merge", "--quiet", outfile, *slice_files], timeout)
        if record["status"] != "ok":
            return record
    for file in slice_files:  # the merge is a slice of them all, itself mergeable further
        if os.path.exists(file):
            os.remove(file)
    return record
