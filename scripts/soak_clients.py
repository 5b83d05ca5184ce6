#!/usr/bin/python3
"""Soak test clients: N processes x M calls of mixed requests against the placement server.

Valid requests with fixed seeds must succeed and equal the answer a lone client got before the
soak; requests that are bad on purpose must fail with their message; the node's RSS is read
before and after. Prints a summary and exits non-zero on any failed valid call or mismatch.
"""
import argparse
import multiprocessing
import os
import sys
import time

import rospy
from geometry_msgs.msg import Pose
from placement_samplers.msg import Fixture
from placement_samplers.srv import SamplePlacements, SamplePlacementsRequest

SERVICE = "/placement_server/sample_placements"
FIXED_SEEDS = list(range(1000, 1020))


def request_kinds():
    """(name, request, expect_success, expected message prefix)"""
    kinds = []
    for seed in FIXED_SEEDS:
        kinds.append(("fixed", SamplePlacementsRequest(seed=seed, dry_run=True), True, ""))
    kinds.append(("batch", SamplePlacementsRequest(seed=77, num_scenes=20, dry_run=True), True, ""))
    kinds.append(("fresh seed", SamplePlacementsRequest(dry_run=False), True, ""))
    kinds.append(("sub-sampler", SamplePlacementsRequest(seed=5, sampler="TableSampler", dry_run=True), True, ""))
    kinds.append(("unknown sampler", SamplePlacementsRequest(sampler="Nope"), False, "unknown sampler 'Nope'"))
    bad = Fixture(name="bad", pose=Pose())
    bad.shape.type = 1
    bad.shape.dimensions = [0.1, 0.1, 0.1]
    kinds.append(("zero quaternion", SamplePlacementsRequest(fixtures=[bad]), False,
                  "fixtures[0].pose.orientation must be a unit quaternion"))
    wall = Fixture(name="wall", pose=Pose())
    wall.pose.orientation.w = 1.0
    wall.pose.position.z = 0.8
    wall.shape.type = 1
    wall.shape.dimensions = [3.0, 3.0, 1.0]
    kinds.append(("blocked", SamplePlacementsRequest(seed=3, sampler="TableSampler", fixtures=[wall],
                                                     max_attempts=20, dry_run=True), False,
                  "could not place object 'cube'"))
    kinds.append(("too many scenes", SamplePlacementsRequest(num_scenes=10 ** 9), False, "num_scenes"))
    return kinds


def client(index, calls, reference, queue):
    rospy.init_node("soak_client_%d" % index, anonymous=True, disable_signals=True)
    proxy = rospy.ServiceProxy(SERVICE, SamplePlacements, persistent=True)
    kinds = request_kinds()
    stats = {"calls": 0, "valid_failed": 0, "mismatch": 0, "bad_accepted": 0, "wrong_message": 0,
             "errors": 0}
    examples = []
    for i in range(calls):
        name, req, ok, prefix = kinds[(i * 7 + index) % len(kinds)]
        try:
            res = proxy(req)
        except Exception as e:  # a dropped connection counts, then reconnect
            stats["errors"] += 1
            examples.append("%s: %s" % (name, e))
            proxy = rospy.ServiceProxy(SERVICE, SamplePlacements, persistent=True)
            continue
        stats["calls"] += 1
        if ok:
            if not res.success:
                stats["valid_failed"] += 1
                examples.append("%s: %s" % (name, res.message))
            elif req.seed in reference and req.num_scenes <= 1 and not req.sampler:
                if res.scenes != reference[req.seed]:
                    stats["mismatch"] += 1
        else:
            if res.success:
                stats["bad_accepted"] += 1
            elif not res.message.startswith(prefix):
                stats["wrong_message"] += 1
                examples.append("%s: %s" % (name, res.message))
    proxy.close()
    queue.put((stats, examples[:5]))


def rss_kb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return -1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--clients", type=int, default=8)
    parser.add_argument("--calls", type=int, default=10000, help="per client")
    parser.add_argument("--node-pid", type=int, required=True)
    args = parser.parse_args()

    rospy.init_node("soak_reference", anonymous=True, disable_signals=True)
    rospy.wait_for_service(SERVICE, timeout=60)
    lone = rospy.ServiceProxy(SERVICE, SamplePlacements)
    reference = {}
    for seed in FIXED_SEEDS:
        res = lone(SamplePlacementsRequest(seed=seed, dry_run=True))
        if not res.success:
            print("reference call failed: %s" % res.message)
            return 1
        reference[seed] = res.scenes
    # Warm up so the RSS baseline includes the node's steady buffers.
    for _ in range(200):
        lone(SamplePlacementsRequest(seed=1, num_scenes=20, dry_run=True))
    rss_before = rss_kb(args.node_pid)

    start = time.time()
    # Fresh interpreters: a forked child would inherit this process's rospy node.
    ctx = multiprocessing.get_context("spawn")
    queue = ctx.Queue()
    procs = [ctx.Process(target=client, args=(i, args.calls, reference, queue))
             for i in range(args.clients)]
    for p in procs:
        p.start()
    results = [queue.get() for _ in procs]
    for p in procs:
        p.join()
    elapsed = time.time() - start
    rss_after = rss_kb(args.node_pid)

    total = {k: sum(r[0][k] for r in results) for k in results[0][0]}
    print("soak: %d clients x %d calls in %.1f s (%.0f calls/s)" % (
        args.clients, args.calls, elapsed, total["calls"] / max(elapsed, 1e-9)))
    for k, v in total.items():
        print("  %-14s %d" % (k, v))
    print("  node RSS before %d kB, after %d kB, growth %d kB" % (rss_before, rss_after,
                                                                rss_after - rss_before))
    for r in results:
        for e in r[1]:
            print("  example: %s" % e)
    bad = (total["valid_failed"] or total["mismatch"] or total["bad_accepted"] or
           total["wrong_message"] or total["errors"] or rss_after - rss_before > 5 * 1024)
    print("soak: %s" % ("FAILED" if bad else "passed"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
