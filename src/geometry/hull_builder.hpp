#pragma once
// The quickhull behind convexHull(): a half-edge mesh grown point by point, with face merging.
// Private to convex_hull.cpp, hull_builder.cpp and hull_merge.cpp.

#include <Eigen/Core>
#include <stdexcept>
#include <vector>

#include "geometry/convex_hull.hpp"

namespace placement_samplers::detail {

enum class HullMark : unsigned char { Active, Visible, Deleted };

struct HalfEdge {
  int head = -1;  ///< the point it points to
  int face = -1;  ///< the face on its left, -1 when free
  int next = -1;
  int prev = -1;
  int twin = -1;
};

struct HullBuilderFace {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double offset = 0.0;
  double area = 0.0;
  int edge = -1;
  int vertexCount = 0;
  int outside = -1;  ///< first point of the points outside it, -1: none
  HullMark mark = HullMark::Active;
  bool nonConvex = false;
};

/// A mesh the merges broke; convexHull() tries again with a larger tolerance.
struct HullInternalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Quickhull (Barber, Dobkin and Huhdanpaa) on a half-edge mesh, with the face merging of
/// Lloyd's QuickHull3D: after each point is added, a new face whose neighbour is coplanar with it
/// or bends outwards (within the tolerance) absorbs that neighbour. The faces stay convex and
/// their planes well defined, which keeps the algorithm robust to coplanar points (the sides of
/// a tessellated box) and gives each flat side as one polygon.
class HullBuilder {
 public:
  /// @p points must outlive the builder; @p tolerance [m] as ConvexHull::tolerance.
  HullBuilder(const std::vector<Eigen::Vector3d>& points, double tolerance)
      : p_(points), tol_(tolerance), nextOutside_(points.size(), -1), mark_(points.size(), 0) {}

  /// The hull, from the tetrahedron @p v0 .. @p v3 (indices of points that span a volume) on:
  /// each step adds the farthest point outside a face.
  /// @throw HullInternalError when merges broke the mesh
  ConvexHull build(int v0, int v1, int v2, int v3);

 private:
  using Face = HullBuilderFace;
  using Mark = HullMark;

  int tail(int e) const { return edges_[edges_[e].prev].head; }
  int twinFace(int e) const { return edges_[edges_[e].twin].face; }
  double distance(int f, const Eigen::Vector3d& q) const {
    return faces_[f].normal.dot(q) - faces_[f].offset;
  }
  /// How far the centroid of the face across @p e lies above the plane of e's face.
  double oppositeCentroidDistance(int e) const {
    return distance(edges_[e].face, faces_[twinFace(e)].centroid);
  }
  [[noreturn]] static void internalError(const char* what) { throw HullInternalError(what); }

  // Growing the hull (hull_builder.cpp).
  int newEdge();
  int newFace();
  /// The triangle a -> b -> c; its first edge goes from a to b. Twins are left unset.
  int addTriangle(int a, int b, int c);
  /// Centroid, area, unit normal and vertex count of face @p f from its edge loop.
  void computePlane(int f);
  void addOutside(int q, int f);
  /// Gives the outside points of the dying face @p f to @p into when outside it, else to the
  /// points the new faces sort out.
  void movePoints(int f, int into);
  void kill(int f);
  void initialSimplex(int v0, int v1, int v2, int v3);
  /// Marks the faces @p eye sees, starting at @p f, and lists the edges of the horizon in order
  /// (a depth-first walk, with a stack of its own: the visible region can be large).
  void computeHorizon(int eye, int f);
  void addPoint(int eye, int f);
  /// Returns the slots of the faces and edges that went to the free lists.
  void recycle();
  ConvexHull output() const;

  // Merging faces (hull_merge.cpp).
  /// Makes @p prev and @p e consecutive edges of face @p f. When both border the same face,
  /// their common vertex is dropped; a triangle that this reduces to an edge goes too (returned).
  int connect(int f, int prev, int e);
  /// Face @p f absorbs the face across its edge @p adjacent.
  void mergeFaces(int f, int adjacent);
  void checkFace(int f) const;
  /// The face across the third edge of the triangle that a merge would reduce to an edge where
  /// edges @p a and @p b meet (both bordering it), -1 when none would.
  int collapseTarget(int a, int b, int& triangle) const;
  /// False when merging face @p f with the face across its edge @p e would break the mesh: the
  /// two touch at a vertex away from their common edges (the merged polygon would pass twice
  /// through it), or a triangle beside them would shrink to an edge next to another face that
  /// goes. Such merges are left out; the faces stay apart, slightly bent.
  bool mergeKeepsSimple(int f, int e);
  /// One merge of face @p f with a neighbour that is coplanar or bends outwards, judged by the
  /// plane of the larger of the two (first pass) or by either (second pass). False when none.
  bool mergeOnce(int f, bool byLargerFace);

  const std::vector<Eigen::Vector3d>& p_;
  const double tol_;
  std::vector<int> nextOutside_;
  std::vector<HalfEdge> edges_;
  std::vector<Face> faces_;
  std::vector<int> freeEdges_, freeFaces_;
  std::vector<int> pending_;  ///< faces that were given outside points
  struct Frame {
    int edge;       ///< the next edge to look across
    int remaining;  ///< edges of the face still to look across
  };
  std::vector<Frame> stack_;  ///< computeHorizon's
  struct Plane {
    Eigen::Vector3d normal;
    double offset;
    int face;
  };
  std::vector<Plane> planes_;  ///< addPoint's: the new faces'
  std::vector<int> mark_;      ///< per point: stamp_ when on the face mergeKeepsSimple looks at
  int stamp_ = 0;
  std::vector<int> horizon_, visible_, newFaces_, unclaimed_, deadEdges_, deadFaces_;
};

}  // namespace placement_samplers::detail
