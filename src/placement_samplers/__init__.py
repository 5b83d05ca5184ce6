"""placement_samplers: robosuite's placement samplers in C++.

placement_samplers.msg and placement_samplers.srv hold the node's messages and services;
placement_samplers.robosuite is robosuite's UniformRandomSampler and
SequentialCompositeSampler on the C++ core, and sample_scenes() for data sets.
"""
