#!/usr/bin/python3
"""Calls the placement service once and prints the scene.

usage: rosrun placement_samplers sample_client.py [--service NAME] [--seed S]
       [--scenes K] [--first-scene N] [--sampler NAME] [--physics MODE] [--dry-run]
"""
import argparse
import sys

import rospy
from placement_samplers.srv import SamplePlacements, SamplePlacementsRequest


# --physics values and the request's constants (SamplePlacements.srv).
PHYSICS = {"none": SamplePlacementsRequest.PHYSICS_NONE,
           "check": SamplePlacementsRequest.PHYSICS_CHECK,
           "settle": SamplePlacementsRequest.PHYSICS_SETTLE}


def bounded(name, high):
    """An argparse type: an integer in [0, high], else a usage error naming the option."""
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError("%s must be an integer, got %r" % (name, text))
        if not 0 <= value <= high:
            raise argparse.ArgumentTypeError("%s must be in [0, %d], got %d" % (name, high, value))
        return value
    return parse


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--service", default="/placement_server/sample_placements")
    parser.add_argument("--seed", type=bounded("--seed", 2**64 - 1), default=0,
                        help="0 = the node picks one")
    parser.add_argument("--scenes", type=bounded("--scenes", 2**32 - 1), default=1)
    parser.add_argument("--first-scene", type=bounded("--first-scene", 2**64 - 1), default=0,
                        help="index of the first scene of the seed to return")
    parser.add_argument("--sampler", default="", help="'' = the root composite")
    parser.add_argument("--physics", choices=sorted(PHYSICS), default="",
                        help="none, check or settle; default: as configured")
    parser.add_argument("--dry-run", action="store_true", help="broadcast nothing")
    parser.add_argument("--timeout", type=float, default=30.0, help="wait for the service [s]")
    args = parser.parse_args(rospy.myargv()[1:])

    rospy.init_node("placement_sample_client", anonymous=True)
    try:
        rospy.wait_for_service(args.service, timeout=args.timeout)
    except rospy.ROSException:
        print("service %s is not available" % args.service, file=sys.stderr)
        return 2
    call = rospy.ServiceProxy(args.service, SamplePlacements)
    request = SamplePlacementsRequest(seed=args.seed, num_scenes=args.scenes,
                                      first_scene=args.first_scene,
                                      sampler=args.sampler, dry_run=args.dry_run,
                                      physics=PHYSICS.get(args.physics,
                                                          SamplePlacementsRequest.PHYSICS_DEFAULT))
    response = call(request)
    print("success: %s  seed: %d  frame: %s" % (response.success, response.seed, response.frame_id))
    if response.message:
        print("message: %s" % response.message)
    for index, scene in enumerate(response.scenes):
        print("scene %d%s%s" % (args.first_scene + index,
                                ("  stable: %s" % scene.stable) if scene.simulated else "",
                                "" if scene.success else "  FAILED: %s" % scene.message))
        for p in scene.placements:
            q = p.pose.orientation
            line = ("  %-12s %-14s xyz [% .4f % .4f % .4f]  xyzw [% .3f % .3f % .3f % .3f]  attempts %d"
                    % (p.name, p.sampler, p.pose.position.x, p.pose.position.y, p.pose.position.z,
                       q.x, q.y, q.z, q.w, p.attempts))
            if p.simulated:  # hidden objects are not simulated
                line += "  moved %.4f m  turned %.3f rad%s" % (p.moved, p.turned,
                                                              "  FALLEN" if p.fallen else "")
            print(line)
    return 0 if response.success else 1


if __name__ == "__main__":
    sys.exit(main())
