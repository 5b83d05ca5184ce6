#!/usr/bin/env python3
"""Time per sample() call from Python: placement_samplers.robosuite against robosuite's code.

robosuite's code is robosuite's own placement_samplers.py when ROBOSUITE_PLACEMENT_SAMPLERS
names it (its few robosuite imports served by test/python/robosuite_api.py's stand-ins), else
test/robosuite_reference.py behind robosuite's API. Both sample the setups of robosuite's Lift
and PickPlace (test/python/robosuite_setups.py) with a Generator each, seeded alike, with
objects whose attributes are plain attributes and with objects that compute them on every
read as robosuite's BoxObject and MujocoXMLObject do. The two are timed in alternating rounds
of the same number of calls; the table gives the median over the rounds of the time per call
and their ratio. Both must give the same results (checked on the calls timed).

    benchmarks/python_speed.py [--calls N] [--rounds R]   (after sourcing devel/setup.bash)
"""

import argparse
import os
import statistics
import sys
import time

import numpy as np

TESTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "test", "python")
sys.path.insert(0, TESTS)

from robosuite_api import REFERENCE, load_robosuite  # noqa: E402 - first: robosuite stand-ins
import robosuite_setups  # noqa: E402
import placement_samplers.robosuite as ours  # noqa: E402


def per_call(sampler, calls):
    """Seconds per sample() call over @p calls calls, and the last result."""
    sample = sampler.sample
    start = time.perf_counter()
    for _ in range(calls):
        result = sample()
    return (time.perf_counter() - start) / calls, result


def same(a, b):
    return list(a) == list(b) and all(
        [float(v) for v in a[k][0]] == [float(v) for v in b[k][0]] and
        np.asarray(a[k][1]).tobytes() == np.asarray(b[k][1]).tobytes() for k in a)


def measure(setup, theirs, objects, calls, rounds):
    rng = np.random.default_rng(1)
    their_rng = np.random.default_rng(1)
    mine = setup(ours, rng, objects)
    other = setup(theirs, their_rng, objects)
    mine_times, their_times = [], []
    for _ in range(rounds + 1):  # the first round warms up
        t_mine, r_mine = per_call(mine, calls)
        t_theirs, r_theirs = per_call(other, calls)
        if not same(r_mine, r_theirs) or rng.bit_generator.state != their_rng.bit_generator.state:
            sys.exit("%s: the results differ" % setup.__name__)
        mine_times.append(t_mine)
        their_times.append(t_theirs)
    return statistics.median(their_times[1:]), statistics.median(mine_times[1:])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=2000, help="calls per round")
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    robosuite = load_robosuite()
    theirs = robosuite if robosuite is not None else REFERENCE
    label = ("robosuite's placement_samplers.py" if robosuite is not None
             else "test/robosuite_reference.py")
    print("| setup | objects | %s [us] | placement_samplers.robosuite [us] | speed-up |" % label)
    print("|---|---|---|---|---|")
    for name in ("lift", "pick_place"):
        for objects, kind in (("plain", "plain attributes"),
                              ("robosuite", "robosuite's properties")):
            t_theirs, t_mine = measure(robosuite_setups.SETUPS[name], theirs, objects,
                                       args.calls, args.rounds)
            print("| %s | %s | %.1f | %.2f | %.0fx |" % (
                {"lift": "Lift", "pick_place": "PickPlace"}[name], kind, t_theirs * 1e6,
                t_mine * 1e6, t_theirs / t_mine))
    print("\n%d rounds of %d calls each, medians; numpy %s, Python %s" % (
        args.rounds, args.calls, np.__version__, sys.version.split()[0]))


if __name__ == "__main__":
    main()
