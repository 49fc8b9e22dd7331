"""The Dask cluster a study or a distributed render runs on, and its progress bar.

Without a scheduler address: a local cluster of worker processes on the local machine, one per
render (each render has its own threads), started and stopped with the run. With
--scheduler tcp://HOST:8786: any running Dask cluster (dask-scheduler plus dask-worker on each
machine, or an SSH, SLURM or Kubernetes deployment); its workers need the binary, the scenes and
the study folder at the same paths (docs/distributed.md).
"""
import contextlib
import os
import sys
import time

LIB = os.path.dirname(os.path.abspath(__file__))


def local_cluster(workers):
    """A cluster of `workers` processes on the local machine, one thread each, quiet, its
    dashboard on a free port (a fixed one would clash with a cluster already running).

    Its workers log only what is critical: a worker's heartbeat that races the shutdown of a
    run that succeeded logs "Scheduler was unaware of this worker" as an error, and every real
    failure reaches the user as its task's outcome (outcome_of) anyway."""
    import logging
    from distributed import LocalCluster
    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        dashboard_address=":0", silence_logs=logging.CRITICAL)


@contextlib.contextmanager
def connect(scheduler=None, workers=None):
    """A distributed.Client; workers: local worker processes (default: one per 2 cores)."""
    import dask
    from distributed import Client
    # Quiet workers: pbrt_ext's failures are reported per task, not as worker logs.
    dask.config.set({"distributed.logging.distributed": "error",
                     "distributed.scheduler.allowed-failures": 3})
    if scheduler:
        client = Client(scheduler)
        cluster = None
    else:
        cluster = local_cluster(workers or max(1, (os.cpu_count() or 2) // 2))
        client = Client(cluster)
    try:
        # Workers import the task module from the file the client sends.
        client.upload_file(os.path.join(LIB, "studytasks.py"))
        yield client
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def failure(message):
    """A task's record where it did not produce one: failed, with why."""
    return {"status": "failed", "message": message, "wall_seconds": None, "seconds": None,
            "relmse": None, "worker": None, "binary_version": None}


def outcome_of(future):
    """The task's result, or, where it raised (its worker died three times, or the task itself
    failed), a failure record with the exception's message."""
    try:
        return future.result()
    except Exception as e:  # noqa: BLE001: every failure is an outcome to report
        return failure(f"{type(e).__name__}: {e}")


class ProgressBar:
    """[#####.....] done/total what, elapsed, ETA: on one line on a terminal, a line every 10 %
    otherwise (CI logs). The bar and the ETA follow the work done, where tasks weigh what they
    cost (a study's: their samples per pixel), not their count."""

    def __init__(self, total, what, stream=sys.stderr, total_work=None):
        self.total, self.what, self.stream = total, what, stream
        self.total_work = total_work if total_work is not None else total
        self.done = 0
        self.work = 0
        self.start = time.monotonic()
        self.tty = stream.isatty()
        self.last_tenth = -1
        self.show()

    def advance(self, work=1):
        self.done += 1
        self.work += work
        self.show()

    def elapsed(self):
        return time.monotonic() - self.start

    @staticmethod
    def _clock(seconds):
        seconds = int(seconds)
        return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"

    def show(self):
        elapsed = time.monotonic() - self.start
        fraction = min(1, self.work / self.total_work) if self.total_work else 1
        if self.done >= self.total:
            fraction = 1
        eta = "?" if self.work == 0 else self._clock(elapsed / self.work * (self.total_work - self.work))
        bar = "#" * int(30 * fraction) + "." * (30 - int(30 * fraction))
        line = (f"[{bar}] {self.done}/{self.total} {self.what}, {self._clock(elapsed)} elapsed, "
                f"ETA {eta}")
        if self.tty:
            self.stream.write("\r" + line + ("\n" if self.done >= self.total else ""))
        elif int(10 * fraction) > self.last_tenth:
            self.last_tenth = int(10 * fraction)
            self.stream.write(line + "\n")
        self.stream.flush()
