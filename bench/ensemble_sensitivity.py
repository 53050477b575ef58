#!/usr/bin/env python3
"""Sensitivity of an ensemble's mean angle to the fit window and bin width (issue 15, item 4).

    python3 bench/ensemble_sensitivity.py ENSEMBLE_DIR [ENSEMBLE_DIR ...]

Each seed's repose.json holds the angle re-measured for 27 fit settings (fit_lower and fit_upper
each -0.05 / 0 / +0.05, bin width 0.5 / 1 / 2 x the run's). A single run moves by up to a few
degrees when its window edge crosses a particle-sized bump; what a comparison of means needs is
how the MEAN over the seeds moves. For every setting this prints the mean over the seeds that
have it, and the largest deviation from the mean at the run's own setting.
"""
import glob
import json
import os
import sys

for folder in sys.argv[1:]:
    runs = []
    for path in sorted(glob.glob(os.path.join(folder, "seed-*", "repose.json"))):
        data = json.load(open(path))
        if data["fit"]["valid"]:
            runs.append(data)
    if not runs:
        print(f"{folder}: no valid runs")
        continue
    settings = {}
    for data in runs:
        for entry in data["sensitivity"]["entries"]:
            if not entry["valid"]:
                continue
            key = (entry["fit_lower"], entry["fit_upper"], entry["bin_factor"])
            settings.setdefault(key, []).append(entry["angle_degrees"])
    reference = sum(d["fit"]["angle_degrees"] for d in runs) / len(runs)
    worst_window = worst_bins = worst = 0.0
    print(f"{folder}: {len(runs)} runs, mean angle {reference:.2f} deg at the run's own setting")
    print("  fit_lower fit_upper bin_factor  runs  mean_deg  deviation_deg")
    for key in sorted(settings):
        angles = settings[key]
        mean = sum(angles) / len(angles)
        deviation = mean - reference
        lower, upper, factor = key
        print(f"  {lower:9.2f} {upper:9.2f} {factor:10.1f} {len(angles):5d} {mean:9.2f} {deviation:+14.2f}")
        worst = max(worst, abs(deviation))
        if factor == 1.0:
            worst_window = max(worst_window, abs(deviation))
        if abs(lower - runs[0]["options"]["fit_lower"]) < 1e-9 and \
                abs(upper - runs[0]["options"]["fit_upper"]) < 1e-9:
            worst_bins = max(worst_bins, abs(deviation))
    print(f"  largest deviation of the mean: {worst:.2f} deg (fit window alone {worst_window:.2f}, "
          f"bin width alone {worst_bins:.2f})")
