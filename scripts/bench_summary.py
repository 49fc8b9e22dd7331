"""Prints the headline numbers of a scripts/bench run from Google Benchmark's JSON files.

Usage: /usr/bin/python3 scripts/bench_summary.py build/bench
"""
import json
import os
import sys


def load(folder, name):
    path = os.path.join(folder, name + ".json")
    with open(path) as f:
        return {b["name"]: b for b in json.load(f)["benchmarks"]}


def main(folder):
    bxdf = load(folder, "bxdf_bench")
    print("\nBxDF calls/s (f, PDF, Sample_f):")
    for label, prefix in [("fabric (best, n=5)", "Fabric/{}/best/n=5"),
                          ("conductor (alpha 0.3)", "Conductor/{}/alpha=0.3"),
                          ("diffuse", "Diffuse/{}")]:
        rates = [bxdf.get(prefix.format(call), {}).get("calls/s", float("nan"))
                 for call in ("f", "PDF", "Sample_f")]
        print(f"  {label:24s}" + "".join(f"{r / 1e6:10.2f} M" for r in rates))
    print("\nRenderer camera samples/s and rays/s:")
    for name, b in load(folder, "render_bench").items():
        print(f"  {name:48s} {b['camera_samples/s'] / 1e6:6.3f} M  {b['rays/s'] / 1e6:6.2f} M rays/s")
    stress = next(iter(load(folder, "stress_bench").values()))
    print(f"\nStress: {stress['calls/s'] / 1e6:.1f} M fabric calls/s, "
          f"{int(stress['nonfinite'])} non-finite, {int(stress['negative'])} negative")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
