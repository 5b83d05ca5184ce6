#!/usr/bin/python3
"""The rospy side: the example client script and the generated Python messages."""
import os
import re
import signal
import subprocess
import sys
import time
import unittest

import rospy
import rostest
from placement_samplers.srv import SamplePlacements, SamplePlacementsRequest

SERVICE = "/placement_server/sample_placements"
CLIENT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "sample_client.py")


class SampleClientTest(unittest.TestCase):
    def setUp(self):
        rospy.wait_for_service(SERVICE, timeout=30.0)

    def test_rospy_call_round_trips_the_seed(self):
        call = rospy.ServiceProxy(SERVICE, SamplePlacements)
        first = call(SamplePlacementsRequest())
        self.assertTrue(first.success, first.message)
        again = call(SamplePlacementsRequest(seed=first.seed, dry_run=True))
        self.assertEqual(first.scenes, again.scenes)
        names = [p.name for p in first.scenes[0].placements]
        self.assertEqual(names, ["plate", "cup", "cube", "can", "ball", "pill"])

    def test_example_client_prints_the_scene(self):
        out = subprocess.run([sys.executable, CLIENT, "--seed", "5", "--dry-run"],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("success: True  seed: 5  frame: world", out.stdout)
        self.assertIn("TableSampler", out.stdout)

    def test_example_client_reports_a_bad_sampler(self):
        out = subprocess.run([sys.executable, CLIENT, "--sampler", "Nope", "--dry-run"],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 1)
        self.assertIn("message: unknown sampler 'Nope'", out.stdout)

    def test_example_client_first_scene_is_that_scene_of_the_seed(self):
        def scenes(*extra):
            out = subprocess.run([sys.executable, CLIENT, "--seed", "5", "--dry-run"] + list(extra),
                                 capture_output=True, text=True, timeout=60)
            self.assertEqual(out.returncode, 0, out.stderr)
            return out.stdout.split("scene ")[1:]
        three = scenes("--scenes", "3")
        third = scenes("--first-scene", "2")
        self.assertEqual(len(three), 3)
        self.assertEqual(third, [three[2]])
        self.assertTrue(third[0].startswith("2\n"))

    def test_example_client_settles_with_physics(self):
        out = subprocess.run([sys.executable, CLIENT, "--seed", "5", "--dry-run", "--physics",
                              "settle"], capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("scene 0  stable: True", out.stdout)
        self.assertIn("moved ", out.stdout)
        plain = subprocess.run([sys.executable, CLIENT, "--seed", "5", "--dry-run"],
                               capture_output=True, text=True, timeout=60)
        self.assertNotIn("stable:", plain.stdout)
        bad = subprocess.run([sys.executable, CLIENT, "--physics", "wobble"],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("--physics: invalid choice: 'wobble'", bad.stderr)

    def test_example_client_refuses_a_negative_seed_with_usage(self):
        out = subprocess.run([sys.executable, CLIENT, "--seed", "-1"],
                             capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 2)
        self.assertIn("--seed must be in [0, 18446744073709551615], got -1", out.stderr)
        self.assertNotIn("Traceback", out.stderr)

    def test_action_prints_what_the_service_prints_with_a_progress_bar(self):
        args = [sys.executable, CLIENT, "--seed", "5", "--scenes", "3", "--dry-run",
                "--physics", "check"]
        service = subprocess.run(args, capture_output=True, text=True, timeout=60)
        action = subprocess.run(args + ["--action"], capture_output=True, text=True, timeout=60)
        self.assertEqual(action.returncode, 0, action.stderr)
        self.assertEqual(action.stdout, service.stdout)
        # tqdm's bar on stderr, its last state: every scene done.
        self.assertIn("3/3", action.stderr.replace("\r", "\n").strip().splitlines()[-1])
        self.assertIn("0 failed", action.stderr)
        self.assertEqual(service.stderr, "")

    def test_action_ctrl_c_cancels_and_prints_the_scenes_done(self):
        # 500 simulated scenes take seconds: the interrupt comes long before the end.
        client = subprocess.Popen([sys.executable, CLIENT, "--action", "--seed", "6", "--scenes",
                                   "500", "--dry-run", "--physics", "check"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.time() + 60
        seen = ""
        while time.time() < deadline and not re.search(r"\b[1-9][0-9]*/500\b", seen):
            seen += os.read(client.stderr.fileno(), 4096).decode()
        client.send_signal(signal.SIGINT)
        out, _ = client.communicate(timeout=60)
        self.assertEqual(client.returncode, 130)
        lines = out.splitlines()
        self.assertEqual(lines[0], "success: False  seed: 6  frame: world")
        self.assertTrue(lines[1].startswith("message: cancelled after "), lines[1])
        done = int(lines[1].split()[3])
        self.assertLess(done, 500)
        self.assertEqual(len([line for line in lines if line.startswith("scene ")]), done)


if __name__ == "__main__":
    rospy.init_node("test_sample_client", anonymous=True)
    rostest.rosrun("placement_samplers", "test_sample_client", SampleClientTest)
