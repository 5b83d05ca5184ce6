#pragma once
// placement_benchmark --only resting: restingPoses() on generated meshes and primitives.

namespace placement_samplers::benchmark {

/// Prints the time restingPoses() takes (median of @p repetitions calls after one warm-up) for a
/// 100,000-triangle ellipsoid mesh (closed and convex: its own hull), the same ellipsoid's
/// 50,002 vertices alone (quickhull), a 100,000-triangle cup (not convex: quickhull), a
/// 99,372-triangle tessellated box whose sides share no
/// vertices (quickhull), a mug (cylinder and box handle), the L-shaped block's vertices and a box,
/// with the number of poses each has (and of rolling ones, listed with allow_rolling).
void benchResting(int repetitions);

}  // namespace placement_samplers::benchmark
