"""scripts/study run: a study's missing references and configurations as Dask tasks.

Each scene's reference is rendered first (its slices and their merge have the higher priority,
and every configuration of the scene waits for it), split into sample slices over the workers
and merged exactly (pbrt_ext merge). Every configuration without a stored result is one task
that runs pbrt_ext and computes relMSE against the reference on its worker. Results are stored
as they arrive (studydb). A configuration that fails is stored as failed with pbrt_ext's
message and not retried (Dask retries a task only when its worker dies, up to three times).
"""
import os
import sys

import studytasks
from studycluster import ProgressBar, outcome_of
from studydb import Database


def _job(study, scene, args):
    return {"binary": study.binary, "scene": scene.path, "args": args, "timeout": study.timeout}


def _submit_reference(client, study, scene):
    """The futures of the scene's slices and of their merge."""
    os.makedirs(os.path.dirname(study.reference_path(scene)), exist_ok=True)
    slices, files = [], []
    for first, last in study.reference_slices_of():
        outfile = study.reference_path(scene).replace(".exr", f".slice{first}-{last}.exr")
        files.append(outfile)
        slices.append(client.submit(studytasks.render_slice,
                                    _job(study, scene, study.reference_args(scene, first, last)),
                                    outfile, pure=False, priority=10))
    merge = client.submit(studytasks.merge_slices, study.binary, study.reference_path(scene),
                          slices, files, study.timeout, pure=False, priority=10)
    return slices, merge


class StudyRun:
    def __init__(self, study, client, database, stream=sys.stderr):
        self.study, self.client, self.db, self.stream = study, client, database, stream
        self.kind = {}           # future -> ("slice", scene) | ("reference", scene, slices) | ("config", key, config)
        self.work = {}           # future -> its samples per pixel, what the progress bar weighs
        self.references = {}     # scene name -> reference path, or the merge's future

    def submit_references(self):
        for scene in self.study.scenes:
            row = self.db.reference(scene.name)
            if row and os.path.exists(row["path"]) and row["spp"] == self.study.reference_spp:
                self.references[scene.name] = row["path"]
                continue
            slices, merge = _submit_reference(self.client, self.study, scene)
            for s, (first, last) in zip(slices, self.study.reference_slices_of()):
                self.kind[s] = ("slice", scene)
                self.work[s] = last - first
            self.kind[merge] = ("reference", scene, slices)
            self.work[merge] = 0
            self.references[scene.name] = merge

    def submit_configurations(self):
        done = self.db.keys()
        todo = 0
        scenes = {s.name: s for s in self.study.scenes}
        for config in self.study.configurations():
            key = self.study.configuration_key(config)
            if key in done:
                continue
            scene = scenes[config["scene"]]
            future = self.client.submit(studytasks.render_configuration,
                                        _job(self.study, scene, self.study.render_args(config)),
                                        self.references[scene.name], pure=False)
            self.kind[future] = ("config", key, config)
            self.work[future] = config["spp"]
            todo += 1
        return todo, len(done)

    def store(self, future):
        """Stores the task's outcome where it is a configuration or a reference; returns it."""
        kind = self.kind[future]
        outcome = outcome_of(future)
        if kind[0] == "config":
            _, key, config = kind
            scene = next(s for s in self.study.scenes if s.name == config["scene"])
            self.db.add_result(key, {**config, **outcome, "scene_hash": scene.hash})
        elif kind[0] == "reference":
            _, scene, slices = kind
            if isinstance(outcome, str):
                records = [outcome_of(s) for s in slices]
                self.db.add_reference({
                    "scene": scene.name, "path": outcome, "spp": self.study.reference_spp,
                    "seed": self.study.reference_seed, "slices": len(slices),
                    "seconds": sum(r["seconds"] or 0 for r in records),
                    "wall_seconds": sum(r["wall_seconds"] or 0 for r in records),
                    "binary_version": records[0].get("binary_version"), "scene_hash": scene.hash})
            else:
                self.stream.write(f"\nreference of {scene.name} failed: {outcome['message']}\n")
        return outcome

    def run(self):
        """Renders what is missing; returns the number of failed configurations stored."""
        from distributed import as_completed
        self.submit_references()
        todo, done = self.submit_configurations()
        self.stream.write(f"study {self.study.name}: {todo} configurations to render, {done} "
                          f"stored; {sum(1 for k in self.kind.values() if k[0] == 'reference')} "
                          f"references to render\n")
        progress = ProgressBar(len(self.kind), "tasks", self.stream, sum(self.work.values()))
        failed = 0
        for future in as_completed(list(self.kind)):
            outcome = self.store(future)
            if self.kind[future][0] == "config" and outcome["status"] == "failed":
                failed += 1
            progress.advance(self.work[future])
        return failed


def run(study, client, retry_failed=False, stream=sys.stderr):
    database = Database(study.database)
    try:
        if retry_failed:
            stream.write(f"forgetting {database.forget_failed()} failed results\n")
        return StudyRun(study, client, database, stream).run()
    finally:
        database.close()
