#!/usr/bin/env python3
"""sample_scenes --output FILE.npz against its JSON lines: numpy.load gives the same doubles.

For every --config given, runs sample_scenes twice with the same arguments (JSON lines, then
--output) and checks that the .npz holds exactly the JSON's scenes: names in the sampler's order,
position and orientation bit for bit, NaN where a failed scene placed nothing, attempts, success,
the scene indices and the seed; the exit status is the same. With --physics-scenes, also runs
--physics check and settle and compares stable, moved, turned, fallen and (settle) the sampled
poses, NaN where a scene was not simulated. Exits non-zero on a difference.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def run(cmd):
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode not in (0, 1):
        sys.exit("%s failed (%d): %s" % (" ".join(cmd), proc.returncode, proc.stderr))
    return proc


def compare(binary, config, extra, directory, expect_failures, expect_hidden):
    """One configuration and argument list; returns a list of differences."""
    base = [binary, "--config", config] + extra
    text = run(base)
    lines = [json.loads(line) for line in text.stdout.splitlines()]
    path = os.path.join(directory, "out.npz")
    binary_run = run(base + ["--output", path])
    problems = []
    if binary_run.stdout:
        problems.append("--output printed to stdout")
    if binary_run.returncode != text.returncode:
        problems.append("exit status %d with --output, %d without"
                        % (binary_run.returncode, text.returncode))
    data = np.load(path)
    names = data["names"]
    if names.dtype.kind != "U":
        problems.append("names are %s, not unicode" % names.dtype)
    names = [str(n) for n in names]
    column = {name: i for i, name in enumerate(names)}
    k, n = len(lines), len(names)
    shapes = {"position": (k, n, 3), "orientation": (k, n, 4), "attempts": (k, n),
              "success": (k,), "scene": (k,), "seed": ()}
    for key, shape in shapes.items():
        if data[key].shape != shape:
            problems.append("%s has shape %s, expected %s" % (key, data[key].shape, shape))
    if problems:
        return problems
    if data["position"].dtype != np.float64 or data["orientation"].dtype != np.float64:
        problems.append("position/orientation are not float64")
    if data["success"].dtype != np.bool_:
        problems.append("success is %s, not bool" % data["success"].dtype)
    failed = hidden = 0
    for row, scene in enumerate(lines):
        if int(data["seed"]) != scene["seed"]:
            problems.append("seed %d, JSON %d" % (int(data["seed"]), scene["seed"]))
        if data["scene"][row] != scene["scene"] or data["success"][row] != scene["success"]:
            problems.append("scene row %d: %s/%s, JSON %s/%s" % (
                row, data["scene"][row], data["success"][row], scene["scene"], scene["success"]))
        failed += not scene["success"]
        placed = set()
        for p in scene["placements"]:
            c = column.get(p["name"])
            if c is None:
                problems.append("scene %d: %s not in names" % (scene["scene"], p["name"]))
                continue
            placed.add(c)
            hidden += p["position"][0] <= -10.0
            # Exact: JSON numbers are the shortest text that reads back as the same double.
            if (data["position"][row, c].tolist() != p["position"]
                    or data["orientation"][row, c].tolist() != p["orientation"]
                    or data["attempts"][row, c] != p["attempts"]):
                problems.append("scene %d, %s: npz %s %s %s, JSON %s %s %s" % (
                    scene["scene"], p["name"], data["position"][row, c].tolist(),
                    data["orientation"][row, c].tolist(), data["attempts"][row, c],
                    p["position"], p["orientation"], p["attempts"]))
        for c in set(range(n)) - placed:
            if not (np.isnan(data["position"][row, c]).all()
                    and np.isnan(data["orientation"][row, c]).all()
                    and data["attempts"][row, c] == 0):
                problems.append("scene %d: %s not placed but not NaN" % (scene["scene"], names[c]))
        if len(problems) > 10:
            break
    if "--physics" in extra:
        problems += compare_physics(data, lines, column, extra[extra.index("--physics") + 1])
    if expect_failures and failed == 0:
        problems.append("no failed scene: the failure case is not tested")
    if expect_hidden and hidden == 0:
        problems.append("no hidden object: the hidden case is not tested")
    return problems


def compare_physics(data, lines, column, mode):
    """The physics members against the JSON lines of a --physics check or settle run."""
    problems = []
    k, n = len(lines), len(column)
    shapes = {"stable": (k,), "moved": (k, n), "turned": (k, n), "fallen": (k, n)}
    if mode == "settle":
        shapes.update({"sampled_position": (k, n, 3), "sampled_orientation": (k, n, 4)})
    elif "sampled_position" in data:
        problems.append("sampled_position written under --physics check")
    for key, shape in shapes.items():
        if key not in data or data[key].shape != shape:
            return problems + ["%s missing or not of shape %s" % (key, shape)]
    simulated = 0
    for row, scene in enumerate(lines):
        if data["stable"][row] != scene["stable"]:
            problems.append("scene %d: stable %s, JSON %s"
                            % (scene["scene"], data["stable"][row], scene["stable"]))
        for p in scene["placements"]:
            c = column[p["name"]]
            if "moved" not in p:
                if not np.isnan(data["moved"][row, c]):
                    problems.append("scene %d, %s: not simulated but moved is a number"
                                    % (scene["scene"], p["name"]))
                continue
            simulated += 1
            got = [data["moved"][row, c], data["turned"][row, c], bool(data["fallen"][row, c])]
            if got != [p["moved"], p["turned"], p["fallen"]]:
                problems.append("scene %d, %s: npz %s, JSON %s" % (
                    scene["scene"], p["name"], got, [p["moved"], p["turned"], p["fallen"]]))
            if mode == "settle" and (
                    data["sampled_position"][row, c].tolist() != p["sampled_position"]
                    or data["sampled_orientation"][row, c].tolist() != p["sampled_orientation"]):
                problems.append("scene %d, %s: sampled pose differs" % (scene["scene"], p["name"]))
    if simulated == 0:
        problems.append("no simulated placement: the physics case is not tested")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sample-scenes", required=True)
    parser.add_argument("--config", action="append", required=True,
                        help="a configuration; NAME:failures or NAME:hidden: it must have some")
    parser.add_argument("--scenes", type=int, default=300)
    parser.add_argument("--physics-scenes", type=int, default=0,
                        help="also run --physics check and settle on this many scenes")
    args = parser.parse_args()
    runs = []
    for spec in args.config:
        path, _, expect = spec.partition(":")
        for extra in (["--seed", "3"], ["--seed", "4294967303", "--first-scene", "1099511627776"],
                      ["--seed", "5", "--collision-check", "fcl", "--threads", "2"]):
            runs.append((path, extra + ["--scenes", str(args.scenes)], expect))
        for mode in ("check", "settle") if args.physics_scenes else ():
            runs.append((path, ["--seed", "6", "--physics", mode, "--threads", "2", "--scenes",
                                str(args.physics_scenes)], expect))
    failures = 0
    with tempfile.TemporaryDirectory() as directory:
        for path, extra, expect in runs:
            problems = compare(args.sample_scenes, path, extra, directory,
                               expect == "failures", expect == "hidden")
            label = "%s %s" % (os.path.basename(path), " ".join(extra))
            print("%s: %s" % (label, "same" if not problems else "DIFFERENT"))
            for p in problems[:10]:
                print("  " + p)
            failures += bool(problems)
    print("%d of %d runs equal" % (len(runs) - failures, len(runs)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
