# The Python package placement_samplers for catkin_python_setup(): the generated messages and
# services, and the extension module placement_samplers.robosuite (built by CMake).
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["placement_samplers"], package_dir={"": "src"}))
