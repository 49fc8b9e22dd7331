#!/usr/bin/env python3
"""Prints the metal eta/k tables of pbrt_ext/spectra.cpp from the excerpts beside this script.

Each metal-<name>.nk file holds rows "wavelength(um) n k" copied from the refractiveindex.info
database (its header names the source file, commit and paper). The renderer reduces these
tabulated spectra to RGB at run time with the same integration it applies to any spectrum a
scene gives (pbrt_ext/spectra.cpp: CIE 1931 2-degree observer under D65, linear sRGB), so this
script only converts units (um -> nm) and formats the rows:

    /usr/bin/python3 data/spectra/nk_to_table.py > /tmp/tables.inc
"""
import pathlib

here = pathlib.Path(__file__).resolve().parent
for path in sorted(here.glob("metal-*.nk")):
    rows = [line.split() for line in path.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    name = path.stem.split("-", 1)[1]
    print(f"// {path.name}")
    print(f"constexpr NKSample k{name}[] = {{")
    for lam_um, n, k in rows:
        print(f"    {{{round(float(lam_um) * 1000, 2):g}, {float(n):g}, {float(k):g}}},")
    print("};")
