"""scripts/study run: a study's missing references and configurations as Dask tasks.

Each scene's reference is rendered first, split into sample slices over the workers (at the
higher priority) and merged exactly (pbrt_ext merge); the scene's configurations are submitted
once its merge is done. Every configuration without a stored result is one task that runs
pbrt_ext and computes relMSE against the reference on its worker; so is every function
integrator table of [functions] without a stored one. Results are stored as they
arrive (studydb). A configuration that fails is stored as failed with pbrt_ext's message and
not retried (Dask retries a task only when its worker dies, up to three times).

No task takes another task's result as an input: the client passes file paths once it has the
outcome, and releases every future it has stored. A worker that dies then loses only the
tasks it was running, which Dask runs again; Debian's Dask 2022.12 could hang or re-run a
finished merge over its deleted slices when a dead worker held results other tasks needed.
"""
import os
import sys

import studytasks
from studycluster import ProgressBar, failure, outcome_of
from studydb import Database


def _job(study, scene, args):
    return {"binary": study.binary, "scene": scene.path, "args": args, "timeout": study.timeout}


class StudyRun:
    def __init__(self, study, client, database, stream=sys.stderr):
        self.study, self.client, self.db, self.stream = study, client, database, stream
        self.kind = {}      # future -> ("slice", scene) | ("merge", scene) | ("config", key, config)
        self.work = {}      # future -> its samples per pixel, what the progress bar weighs
        self.todo = {}      # scene name -> [(key, config)] without a stored result
        self.function_todo = []  # [(key, config)] of [functions] without a stored table
        self.slices = {}    # scene name -> the outcomes of its reference's finished slices
        self.progress = None

    def plan(self):
        """The configurations to render, by scene; their count and the stored ones' count."""
        done = self.db.keys()
        self.todo = {scene.name: [] for scene in self.study.scenes}
        for config in self.study.configurations():
            key = self.study.configuration_key(config)
            if key not in done:
                self.todo[config["scene"]].append((key, config))
        tables = self.db.function_keys()
        self.function_todo = [(self.study.function_key(c), c) for c in self.study.function_configurations()
                              if self.study.function_key(c) not in tables]
        todo = sum(len(t) for t in self.todo.values()) + len(self.function_todo)
        return todo, len(done) + len(tables)

    def stored_reference(self, scene):
        row = self.db.reference(scene.name)
        if row and os.path.exists(row["path"]) and row["spp"] == self.study.reference_spp:
            return row["path"]
        return None

    def submit(self, function, *args, kind, work, priority=0):
        future = self.client.submit(function, *args, pure=False, priority=priority)
        self.kind[future], self.work[future] = kind, work
        return future

    def slice_file(self, scene, first, last):
        return self.study.reference_path(scene).replace(".exr", f".slice{first}-{last}.exr")

    def submit_slices(self, scene):
        os.makedirs(os.path.dirname(self.study.reference_path(scene)), exist_ok=True)
        self.slices[scene.name] = []
        return [self.submit(studytasks.render_slice,
                            _job(self.study, scene, self.study.reference_args(scene, first, last)),
                            self.slice_file(scene, first, last), kind=("slice", scene),
                            work=last - first, priority=10)
                for first, last in self.study.reference_slices_of()]

    def submit_configurations(self, scene, reference):
        return [self.submit(studytasks.render_configuration,
                            _job(self.study, scene, self.study.render_args(config)), reference,
                            kind=("config", key, config), work=config["spp"])
                for key, config in self.todo[scene.name]]

    def submit_functions(self):
        return [self.submit(studytasks.function_table, self.study.binary, self.study.function_scene(c),
                            self.study.function_args(c), self.study.timeout,
                            kind=("function", key, c), work=c["spp"])
                for key, c in self.function_todo]

    def store_result(self, key, config, outcome):
        scene = next(s for s in self.study.scenes if s.name == config["scene"])
        self.db.add_result(key, {**config, **outcome, "scene_hash": scene.hash})

    def reference_failed(self, scene, message):
        """Stores every configuration of the scene as failed, without rendering it."""
        self.stream.write(f"\nreference of {scene.name} failed: {message}\n")
        for key, config in self.todo[scene.name]:
            self.store_result(key, config, failure("no reference: " + message))
            self.progress.advance(config["spp"])

    def slice_done(self, scene, outcome):
        """Once every slice is in: the merge's future, or none where a slice failed."""
        records = self.slices[scene.name]
        records.append(outcome)
        if len(records) < len(self.study.reference_slices_of()):
            return []
        failed = [r for r in records if r["status"] != "ok"]
        if failed:
            self.reference_failed(scene, "a slice failed: " + failed[0]["message"])
            return []
        files = [self.slice_file(scene, first, last)
                 for first, last in self.study.reference_slices_of()]
        return [self.submit(studytasks.merge_slices, self.study.binary,
                            self.study.reference_path(scene), files, self.study.timeout,
                            kind=("merge", scene), work=0, priority=10)]

    def merge_done(self, scene, outcome):
        """Stores the reference; the futures of the scene's configurations."""
        if outcome["status"] != "ok":
            self.reference_failed(scene, outcome["message"])
            return []
        records = self.slices.pop(scene.name)
        self.db.add_reference({
            "scene": scene.name, "path": self.study.reference_path(scene),
            "spp": self.study.reference_spp, "seed": self.study.reference_seed,
            "slices": len(records), "seconds": sum(r["seconds"] or 0 for r in records),
            "wall_seconds": sum(r["wall_seconds"] or 0 for r in records),
            "binary_version": records[0].get("binary_version"), "scene_hash": scene.hash})
        return self.submit_configurations(scene, self.study.reference_path(scene))

    def finish(self, future):
        """Stores the task's outcome and releases its future; the futures it unblocks."""
        kind, work = self.kind.pop(future), self.work.pop(future)
        outcome = outcome_of(future)
        future.release()  # a finished task is not run again when its worker dies later
        self.progress.advance(work)
        if kind[0] == "slice":
            return self.slice_done(kind[1], outcome)
        if kind[0] == "merge":
            return self.merge_done(kind[1], outcome)
        if kind[0] == "function":
            self.db.add_function_result(kind[1], kind[2], outcome)
            return []
        _, key, config = kind
        self.store_result(key, config, outcome)
        return []

    def run(self):
        """Renders what is missing; returns the number of failed configurations stored."""
        from distributed import as_completed
        todo, done = self.plan()
        pending, references, work = as_completed(), 0, sum(
            c["spp"] for t in self.todo.values() for _, c in t) + sum(
            c["spp"] for _, c in self.function_todo)
        for scene in self.study.scenes:
            reference = self.stored_reference(scene)
            if reference:
                futures = self.submit_configurations(scene, reference)
            else:
                futures = self.submit_slices(scene)
                references += 1
                work += self.study.reference_spp
            for future in futures:
                pending.add(future)
        for future in self.submit_functions():
            pending.add(future)
        self.stream.write(f"study {self.study.name}: {todo} configurations to render, {done} "
                          f"stored; {references} references to render\n")
        tasks = todo + references * (len(self.study.reference_slices_of()) + 1)
        self.progress = ProgressBar(tasks, "tasks", self.stream, work)
        for future in pending:
            for unblocked in self.finish(future):
                pending.add(unblocked)
        tables = {k for k, _ in self.function_todo}
        failed_tables = sum(1 for r in self.db.function_results()
                            if r["status"] == "failed" and r["key"] in tables)
        return len(self.db.keys("failed") & {k for t in self.todo.values() for k, _ in t}) + failed_tables


def run(study, client, retry_failed=False, stream=sys.stderr):
    database = Database(study.database)
    try:
        if retry_failed:
            stream.write(f"forgetting {database.forget_failed()} failed results\n")
        return StudyRun(study, client, database, stream).run()
    finally:
        database.close()
