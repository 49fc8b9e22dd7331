"""A study's results in SQLite, beside the study file (<study>.study/results.sqlite): the renders'
relMSE, the references, and the function integrator's error tables.

One row per configuration, keyed by the configuration (studyfile.Study.configuration_key): a
result is inserted once and never replaced, so a rerun after a stop or a fault neither loses
nor duplicates one. Each row is committed as it arrives, so the database holds every finished
render whenever the study stops (Ctrl-C, a killed client). Only the client writes.
"""
import datetime
import json
import os
import sqlite3

SCHEMA = """
CREATE TABLE IF NOT EXISTS results (
    key TEXT PRIMARY KEY,
    scene TEXT NOT NULL, strategy TEXT, fabric_sampler TEXT, light_sampler TEXT,
    sampler TEXT, integrator TEXT, spp INTEGER NOT NULL, seed INTEGER NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('ok', 'failed')),
    seconds REAL,          -- the render's own time (scene loading excluded)
    wall_seconds REAL,     -- the task's: process start, loading, rendering, relMSE
    relmse REAL,
    message TEXT,          -- pbrt_ext's error where it failed
    worker TEXT, binary_version TEXT, scene_hash TEXT,
    finished_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS function_results (
    key TEXT PRIMARY KEY,
    function TEXT NOT NULL, sampler TEXT NOT NULL, spp INTEGER NOT NULL, seed INTEGER NOT NULL,
    status TEXT NOT NULL CHECK (status IN ('ok', 'failed')),
    rows TEXT,             -- JSON [[samples, mse], ...]: the function integrator's table
    wall_seconds REAL, message TEXT, worker TEXT, binary_version TEXT,
    finished_at TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS study_references (
    scene TEXT PRIMARY KEY, path TEXT NOT NULL, spp INTEGER, seed INTEGER, slices INTEGER,
    seconds REAL, wall_seconds REAL, binary_version TEXT, scene_hash TEXT,
    finished_at TEXT NOT NULL
);
"""
RESULT_FIELDS = ["scene", "strategy", "fabric_sampler", "light_sampler", "sampler", "integrator",
                 "spp", "seed", "status", "seconds", "wall_seconds", "relmse", "message",
                 "worker", "binary_version", "scene_hash"]


def _now():
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


class Database:
    def __init__(self, path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        self.connection = sqlite3.connect(path)
        self.connection.row_factory = sqlite3.Row
        self.connection.executescript(SCHEMA)

    def close(self):
        self.connection.close()

    def keys(self, status=None):
        query = "SELECT key FROM results" + (" WHERE status = ?" if status else "")
        return {row["key"] for row in self.connection.execute(query, (status,) if status else ())}

    def forget_failed(self):
        """Drops the failed results, so that a run renders them again (--retry-failed)."""
        with self.connection:
            return self.connection.execute("DELETE FROM results WHERE status = 'failed'").rowcount

    def add_result(self, key, row):
        """Inserts the result unless one is stored for key; True if inserted."""
        values = [row.get(f) for f in RESULT_FIELDS]
        with self.connection:
            cursor = self.connection.execute(
                f"INSERT OR IGNORE INTO results (key, {', '.join(RESULT_FIELDS)}, finished_at) "
                f"VALUES (?, {', '.join('?' * len(RESULT_FIELDS))}, ?)", [key, *values, _now()])
        return cursor.rowcount == 1

    def results(self):
        return [dict(row) for row in self.connection.execute("SELECT * FROM results ORDER BY rowid")]

    def function_keys(self):
        return {row["key"] for row in self.connection.execute("SELECT key FROM function_results")}

    def add_function_result(self, key, config, record):
        """Inserts the function integrator's table unless one is stored for key."""
        fields = ["function", "sampler", "spp", "seed"]
        values = [config[f] for f in fields] + [
            record["status"], json.dumps(record.get("rows")), record.get("wall_seconds"),
            record.get("message"), record.get("worker"), record.get("binary_version")]
        with self.connection:
            self.connection.execute(
                "INSERT OR IGNORE INTO function_results (key, function, sampler, spp, seed, status, "
                "rows, wall_seconds, message, worker, binary_version, finished_at) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)", [key, *values, _now()])

    def function_results(self):
        rows = [dict(row) for row in self.connection.execute(
            "SELECT * FROM function_results ORDER BY rowid")]
        for row in rows:
            row["rows"] = json.loads(row["rows"]) if row["rows"] else None
        return rows

    def reference(self, scene):
        row = self.connection.execute("SELECT * FROM study_references WHERE scene = ?",
                                      (scene,)).fetchone()
        return dict(row) if row else None

    def add_reference(self, row):
        fields = ["scene", "path", "spp", "seed", "slices", "seconds", "wall_seconds",
                  "binary_version", "scene_hash"]
        with self.connection:
            self.connection.execute(
                f"INSERT OR REPLACE INTO study_references ({', '.join(fields)}, finished_at) "
                f"VALUES ({', '.join('?' * len(fields))}, ?)", [row.get(f) for f in fields] + [_now()])

    def references(self):
        return [dict(row) for row in self.connection.execute("SELECT * FROM study_references")]
