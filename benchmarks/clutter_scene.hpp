#pragma once

// The clutter scene of the benchmarks (placement_benchmark, output_benchmark). Not installed.

#include <sstream>
#include <string>

namespace bench {

/// The clutter scene: @p n cylinders (radius 0.03 m, height 0.1 m) in one sampler over a
/// square region of half width @p half [m] (0.6 m x 0.6 m by default),
/// ensure_object_boundary_in_range and ensure_valid_placement on, reference z 0.8 m, as YAML
/// for the same builder as the files in config/.
inline std::string clutterYaml(int n, double half = 0.3) {
  std::ostringstream y;
  y << "collision_check: radius\nmax_attempts: 5000\nobjects:\n";
  for (int i = 0; i < n; ++i) {
    y << "  cyl" << i << ": {shape: cylinder, radius: 0.03, length: 0.1}\n";
  }
  y << "samplers:\n  - name: ClutterSampler\n    objects: [";
  for (int i = 0; i < n; ++i) {
    y << (i ? ", " : "") << "cyl" << i;
  }
  y << "]\n    x_range: [" << -half << ", " << half << "]\n    y_range: [" << -half << ", " << half
    << "]\n"
       "    rotation_axis: z\n    ensure_object_boundary_in_range: true\n"
       "    ensure_valid_placement: true\n    reference_pos: [0.0, 0.0, 0.8]\n    z_offset: 0.0\n";
  return y.str();
}

}  // namespace bench
