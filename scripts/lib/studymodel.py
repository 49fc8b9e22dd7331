"""scripts/study model: the makespan of a study on N workers, predicted from its measured task
times, and checked by replaying those times on a local cluster of N worker processes.

The tasks are the study's (studyrun): per scene, its reference's slices, then their merge, then
its configurations, which wait for the merge; the reference tasks go first (Dask's priority),
each group in submission order. The model is list scheduling, as Dask's scheduler does it: a
worker that frees takes the first ready task of the highest priority. Task times are the
database's wall seconds (process start, loading, rendering, relMSE: everything a worker spends).

The replay runs the same graph on a local cluster of N worker processes the way the study does
(each task submitted once the tasks it waits for are done), each task sleeping for its time x
scale: sleeping leaves the cores free, so N processes on this machine behave as N machines
would, Dask's own scheduling and communication costs included.
"""
import heapq
import time

from studycluster import local_cluster
from studydb import Database

MERGE_SECONDS = 0.1  # a merge reads and writes a few EXRs


def study_tasks(study):
    """[(name, seconds, priority, [dependency names])] in submission order, from the database."""
    database = Database(study.database)
    results, references = database.results(), {r["scene"]: r for r in database.references()}
    database.close()
    tasks = []
    for scene in study.scenes:
        ref = references.get(scene.name)
        if not ref:
            continue
        slices = [f"{scene.name}/slice{i}" for i in range(ref["slices"])]
        for name in slices:
            tasks.append((name, ref["wall_seconds"] / ref["slices"], 10, []))
        tasks.append((f"{scene.name}/merge", MERGE_SECONDS, 10, slices))
    for i, r in enumerate(results):
        if r["status"] == "ok" and r["scene"] in references:
            tasks.append((f"config{i}", r["wall_seconds"], 0, [f"{r['scene']}/merge"]))
    return tasks


def predict(tasks, workers):
    """The makespan of list scheduling on `workers` workers."""
    done_at = {}
    pending = list(tasks)
    free = [0.0] * workers  # when each worker frees, a heap
    while pending:
        now = heapq.heappop(free)
        ready = [t for t in pending if all(done_at.get(d, float("inf")) <= now for d in t[3])]
        if not ready:  # this worker idles until the next task finishes
            heapq.heappush(free, min(v for v in done_at.values() if v > now))
            continue
        task = max(ready, key=lambda t: t[2])  # the first of the highest priority
        pending.remove(task)
        done_at[task[0]] = now + task[1]
        heapq.heappush(free, done_at[task[0]])
    return max(done_at.values(), default=0.0)


def _sleep(seconds):
    time.sleep(seconds)
    return seconds


def dask_seconds_per_task(count=500):
    """What Dask adds to a task: empty tasks through one local worker process, per task."""
    from distributed import Client, wait
    with local_cluster(1) as cluster, Client(cluster) as client:
        client.wait_for_workers(1)
        start = time.perf_counter()
        wait([client.submit(_sleep, 0, pure=False) for _ in range(count)])
        return (time.perf_counter() - start) / count


def replay(tasks, workers, scale):
    """The measured makespan of the graph with each task sleeping seconds x scale, on a local
    cluster of `workers` processes (its start-up not counted)."""
    from distributed import Client, as_completed
    waits_for = {name: len(dependencies) for name, _, _, dependencies in tasks}
    dependents = {name: [] for name, _, _, _ in tasks}
    for task in tasks:
        for dependency in task[3]:
            dependents[dependency].append(task)
    with local_cluster(workers) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers)
        names, pending = {}, as_completed()

        def submit(task):
            future = client.submit(_sleep, task[1] * scale, priority=task[2], pure=False)
            names[future] = task[0]
            pending.add(future)

        start = time.perf_counter()
        for task in tasks:
            if not task[3]:
                submit(task)
        for future in pending:
            for task in dependents[names.pop(future)]:
                waits_for[task[0]] -= 1
                if waits_for[task[0]] == 0:
                    submit(task)
            future.release()
        return time.perf_counter() - start


def model(study, worker_counts, scale=None):
    tasks = study_tasks(study)
    if not tasks:
        print(f"{study.database}: no measured tasks yet (scripts/study run {study.path})")
        return 1
    total = sum(t[1] for t in tasks)
    longest = max(t[1] for t in tasks)
    print(f"# Makespan of study {study.name}\n\n{len(tasks)} tasks, {total:.1f} s of work, the "
          f"longest {longest:.2f} s.")
    if scale:
        print(f"Dask's own cost: {1000 * dask_seconds_per_task():.1f} ms per task (empty tasks "
              "on one local worker).")
    print()
    header = "| workers | predicted [s] | work / workers [s] | efficiency |"
    if scale:
        header += f" replayed x{scale:g} [s] | predicted x{scale:g} [s] |"
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for n in worker_counts:
        predicted = predict(tasks, n)
        row = f"| {n} | {predicted:.1f} | {total / n:.1f} | {total / n / predicted:.2f} |"
        if scale:
            scaled = [(name, s * scale, p, d) for name, s, p, d in tasks]
            row += f" {replay(tasks, n, scale):.2f} | {predict(scaled, n):.2f} |"
        print(row)
    return 0
