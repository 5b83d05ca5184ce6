#!/usr/bin/python3
"""Calls the placement service once and prints the scene.

usage: rosrun placement_samplers sample_client.py [--service NAME] [--seed S]
       [--scenes K] [--first-scene N] [--sampler NAME] [--physics MODE] [--dry-run]
       [--action]

With --action the request goes to the node's ~sample action instead: a progress bar on
stderr while it samples, and Ctrl-C cancels the goal (the scenes done so far are printed,
exit status 130).
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
    parser.add_argument("--action", action="store_true",
                        help="use the node's ~sample action (next to --service): a progress "
                             "bar, and Ctrl-C cancels")
    args = parser.parse_args(rospy.myargv()[1:])

    fields = dict(seed=args.seed, num_scenes=args.scenes, first_scene=args.first_scene,
                  sampler=args.sampler, dry_run=args.dry_run,
                  physics=PHYSICS.get(args.physics, SamplePlacementsRequest.PHYSICS_DEFAULT))
    if args.action:
        # Ctrl-C must reach the code below (to cancel the goal), not stop rospy at once.
        rospy.init_node("placement_sample_client", anonymous=True, disable_signals=True)
        return run_action(args, fields)
    rospy.init_node("placement_sample_client", anonymous=True)
    try:
        rospy.wait_for_service(args.service, timeout=args.timeout)
    except rospy.ROSException:
        print("service %s is not available" % args.service, file=sys.stderr)
        return 2
    call = rospy.ServiceProxy(args.service, SamplePlacements)
    response = call(SamplePlacementsRequest(**fields))
    print_answer(args, response)
    return 0 if response.success else 1


def run_action(args, fields):
    """Sends the request as a goal of ~sample with a progress bar; Ctrl-C cancels it."""
    import actionlib
    from placement_samplers.msg import SampleScenesAction, SampleScenesGoal
    from tqdm import tqdm

    name = args.service.rsplit("/", 1)[0] + "/sample"
    client = actionlib.SimpleActionClient(name, SampleScenesAction)
    if not client.wait_for_server(rospy.Duration(args.timeout)):
        print("action %s is not available" % name, file=sys.stderr)
        return 2
    bar = tqdm(total=max(args.scenes, 1), unit="scene", file=sys.stderr, dynamic_ncols=True)

    def feedback(f):
        bar.n = f.scenes_done
        bar.set_postfix_str("%d failed" % f.scenes_failed, refresh=False)
        bar.refresh()

    interrupted = False
    try:
        client.send_goal(SampleScenesGoal(**fields), feedback_cb=feedback)
        while not client.wait_for_result(rospy.Duration(0.1)):
            pass
    except KeyboardInterrupt:
        # The node stops at the next scene and answers the scenes done so far.
        interrupted = True
        client.cancel_goal()
        client.wait_for_result(rospy.Duration(args.timeout))
    result = client.get_result()
    if result is not None:
        bar.n = len(result.scenes)
    bar.close()
    if result is None:
        print("no result from %s" % name, file=sys.stderr)
        return 2
    print_answer(args, result)
    if interrupted:
        return 130
    return 0 if result.success else 1


def print_answer(args, response):
    """The service's response or the action's result (the same fields)."""
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


if __name__ == "__main__":
    sys.exit(main())
