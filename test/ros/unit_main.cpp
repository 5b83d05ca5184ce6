// main() of placement_samplers_ros_test: the ROS layer's tests that need no master.

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
