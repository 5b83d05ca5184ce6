#include "geometry/convex_hull.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

// Quickhull (Barber, Dobkin and Huhdanpaa) on a half-edge mesh, with the face merging of
// Lloyd's QuickHull3D: after each point is added, a new face whose neighbour is coplanar with it
// or bends outwards (within the tolerance) absorbs that neighbour. The faces stay convex and
// their planes well defined, which keeps the algorithm robust to coplanar points (the sides of
// a tessellated box) and gives each flat side as one polygon.

namespace placement_samplers::detail {
namespace {

constexpr double kRelativeTolerance = 1e-6;
/// The factor between the tolerances of the attempts convexHull() makes.
constexpr double kRetryFactor = 100.0;

enum class Mark : unsigned char { Active, Visible, Deleted };

struct HalfEdge {
  int head = -1;  ///< the point it points to
  int face = -1;  ///< the face on its left, -1 when free
  int next = -1;
  int prev = -1;
  int twin = -1;
};

struct Face {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double offset = 0.0;
  double area = 0.0;
  int edge = -1;
  int vertexCount = 0;
  int outside = -1;  ///< first point of the points outside it, -1: none
  Mark mark = Mark::Active;
  bool nonConvex = false;
};

/// A mesh the merges broke; convexHull() tries again with a larger tolerance.
struct InternalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void internalError(const char* what) { throw InternalError(what); }

class HullBuilder {
 public:
  HullBuilder(const std::vector<Eigen::Vector3d>& points, double tolerance)
      : p_(points), tol_(tolerance), nextOutside_(points.size(), -1), mark_(points.size(), 0) {}

  ConvexHull build(int v0, int v1, int v2, int v3) {
    initialSimplex(v0, v1, v2, v3);
    while (!pending_.empty()) {
      const int f = pending_.back();
      pending_.pop_back();
      if (faces_[f].mark != Mark::Active || faces_[f].outside < 0) {
        continue;
      }
      // The farthest of its outside points, taken out of the list.
      int best = -1, bestPrev = -1;
      double bestDistance = -1.0;
      for (int q = faces_[f].outside, prev = -1; q >= 0; prev = q, q = nextOutside_[q]) {
        const double d = distance(f, p_[q]);
        if (d > bestDistance) {
          bestDistance = d;
          best = q;
          bestPrev = prev;
        }
      }
      (bestPrev < 0 ? faces_[f].outside : nextOutside_[bestPrev]) = nextOutside_[best];
      if (bestDistance <= tol_) {  // a merge moved the plane past it: on the hull already
        if (faces_[f].outside >= 0) {
          pending_.push_back(f);
        }
        continue;
      }
      addPoint(best, f);
    }
    return output();
  }

 private:
  int tail(int e) const { return edges_[edges_[e].prev].head; }
  int twinFace(int e) const { return edges_[edges_[e].twin].face; }
  double distance(int f, const Eigen::Vector3d& q) const {
    return faces_[f].normal.dot(q) - faces_[f].offset;
  }
  /// How far the centroid of the face across @p e lies above the plane of e's face.
  double oppositeCentroidDistance(int e) const {
    return distance(edges_[e].face, faces_[twinFace(e)].centroid);
  }

  int newEdge() {
    if (!freeEdges_.empty()) {
      const int e = freeEdges_.back();
      freeEdges_.pop_back();
      return e;
    }
    edges_.emplace_back();
    return static_cast<int>(edges_.size()) - 1;
  }

  int newFace() {
    int f;
    if (!freeFaces_.empty()) {
      f = freeFaces_.back();
      freeFaces_.pop_back();
      faces_[f] = Face();
    } else {
      faces_.emplace_back();
      f = static_cast<int>(faces_.size()) - 1;
    }
    return f;
  }

  /// The triangle a -> b -> c; its first edge goes from a to b. Twins are left unset.
  int addTriangle(int a, int b, int c) {
    const int f = newFace();
    const int e[3] = {newEdge(), newEdge(), newEdge()};
    const int heads[3] = {b, c, a};
    for (int k = 0; k < 3; ++k) {
      edges_[e[k]] = HalfEdge{heads[k], f, e[(k + 1) % 3], e[(k + 2) % 3], -1};
    }
    faces_[f].edge = e[0];
    computePlane(f);
    return f;
  }

  /// Centroid, area, unit normal and vertex count of face @p f from its edge loop.
  void computePlane(int f) {
    Face& face = faces_[f];
    const int e0 = face.edge;
    if (edges_[edges_[edges_[e0].next].next].next == e0) {  // a triangle, the common case
      const Eigen::Vector3d& a = p_[tail(e0)];
      const Eigen::Vector3d& b = p_[edges_[e0].head];
      const Eigen::Vector3d& c = p_[edges_[edges_[e0].next].head];
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double norm = n.norm();
      face.vertexCount = 3;
      face.centroid = (a + b + c) / 3.0;
      face.area = 0.5 * norm;
      face.normal = norm > 0.0 ? Eigen::Vector3d(n / norm) : Eigen::Vector3d::Zero();
      face.offset = face.normal.dot(face.centroid);
      return;
    }
    const Eigen::Vector3d& origin = p_[tail(face.edge)];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d twiceArea = Eigen::Vector3d::Zero();
    int count = 0;
    int e = face.edge;
    do {
      sum += p_[edges_[e].head];
      twiceArea += (p_[tail(e)] - origin).cross(p_[edges_[e].head] - origin);
      e = edges_[e].next;
      if (++count > static_cast<int>(edges_.size())) {
        internalError("an open edge loop");
      }
    } while (e != face.edge);
    face.vertexCount = count;
    face.centroid = sum / count;
    const double norm = twiceArea.norm();
    face.area = 0.5 * norm;
    face.normal = norm > 0.0 ? Eigen::Vector3d(twiceArea / norm) : Eigen::Vector3d::Zero();
    face.offset = face.normal.dot(face.centroid);
  }

  void addOutside(int q, int f) {
    if (faces_[f].outside < 0) {
      pending_.push_back(f);
    }
    nextOutside_[q] = faces_[f].outside;
    faces_[f].outside = q;
  }

  /// Gives the outside points of the dying face @p f to @p into when outside it, else to the
  /// points the new faces sort out.
  void movePoints(int f, int into) {
    int q = faces_[f].outside;
    faces_[f].outside = -1;
    while (q >= 0) {
      const int next = nextOutside_[q];
      if (into >= 0 && distance(into, p_[q]) > tol_) {
        addOutside(q, into);
      } else {
        unclaimed_.push_back(q);
      }
      q = next;
    }
  }

  void kill(int f) {
    if (faces_[f].mark == Mark::Active) {
      faces_[f].mark = Mark::Deleted;
      deadFaces_.push_back(f);
    }
  }

  void initialSimplex(int v0, int v1, int v2, int v3) {
    const int tri[4][4] = {{v0, v1, v2, v3}, {v0, v1, v3, v2}, {v0, v2, v3, v1}, {v1, v2, v3, v0}};
    int created[4];
    for (int k = 0; k < 4; ++k) {
      int a = tri[k][0], b = tri[k][1], c = tri[k][2];
      const Eigen::Vector3d n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
      if (n.dot(p_[tri[k][3]] - p_[a]) > 0.0) {
        std::swap(b, c);  // the fourth point must lie behind the face
      }
      created[k] = addTriangle(a, b, c);
    }
    for (int f : created) {
      for (int g : created) {
        for (int e = faces_[f].edge, i = 0; i < 3; e = edges_[e].next, ++i) {
          for (int x = faces_[g].edge, j = 0; j < 3; x = edges_[x].next, ++j) {
            if (edges_[e].head == tail(x) && tail(e) == edges_[x].head) {
              edges_[e].twin = x;
            }
          }
        }
      }
    }
    for (int q = 0; q < static_cast<int>(p_.size()); ++q) {
      if (q == v0 || q == v1 || q == v2 || q == v3) {
        continue;
      }
      int best = -1;
      double bestDistance = tol_;
      for (int f : created) {
        const double d = distance(f, p_[q]);
        if (d > bestDistance) {
          bestDistance = d;
          best = f;
        }
      }
      if (best >= 0) {
        addOutside(q, best);
      }
    }
  }

  /// Marks the faces @p eye sees, starting at @p f, and lists the edges of the horizon in order
  /// (a depth-first walk, with a stack of its own: the visible region can be large).
  void computeHorizon(int eye, int f) {
    std::vector<Frame>& stack = stack_;
    stack.clear();
    faces_[f].mark = Mark::Visible;
    visible_.push_back(f);
    movePoints(f, -1);
    stack.push_back({faces_[f].edge, faces_[f].vertexCount});
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.remaining == 0) {
        stack.pop_back();
        continue;
      }
      const int e = top.edge;
      top.edge = edges_[e].next;
      --top.remaining;
      const int opposite = twinFace(e);
      if (faces_[opposite].mark != Mark::Active) {
        continue;
      }
      if (distance(opposite, p_[eye]) > tol_) {
        faces_[opposite].mark = Mark::Visible;
        visible_.push_back(opposite);
        movePoints(opposite, -1);
        // Around the face from the edge after the one we came through.
        stack.push_back({edges_[edges_[e].twin].next, faces_[opposite].vertexCount - 1});
      } else {
        horizon_.push_back(e);
      }
    }
  }

  /// Makes @p prev and @p e consecutive edges of face @p f. When both border the same face,
  /// their common vertex is dropped; a triangle that this reduces to an edge goes too (returned).
  int connect(int f, int prev, int e) {
    if (twinFace(prev) != twinFace(e)) {
      edges_[prev].next = e;
      edges_[e].prev = prev;
      return -1;
    }
    const int opposite = twinFace(e);
    int discarded = -1;
    int oppositeEdge;
    if (faces_[f].edge == prev) {
      faces_[f].edge = e;
    }
    const int t = edges_[e].twin;
    if (faces_[opposite].vertexCount == 3) {
      oppositeEdge = edges_[edges_[t].prev].twin;
      deadEdges_.insert(deadEdges_.end(), {t, edges_[t].next, edges_[t].prev});
      kill(opposite);
      discarded = opposite;
    } else {
      oppositeEdge = edges_[t].next;
      if (faces_[opposite].edge == t) {
        faces_[opposite].edge = oppositeEdge;
      }
      edges_[oppositeEdge].prev = edges_[t].prev;
      edges_[edges_[t].prev].next = oppositeEdge;
      deadEdges_.push_back(t);
    }
    deadEdges_.push_back(prev);
    edges_[e].prev = edges_[prev].prev;
    edges_[edges_[e].prev].next = e;
    edges_[e].twin = oppositeEdge;
    edges_[oppositeEdge].twin = e;
    if (discarded < 0) {
      computePlane(opposite);
    }
    return discarded;
  }

  /// Face @p f absorbs the face across its edge @p adjacent.
  void mergeFaces(int f, int adjacent) {
    const int across = edges_[adjacent].twin;
    const int other = edges_[across].face;
    kill(other);
    int adjacentPrev = edges_[adjacent].prev, adjacentNext = edges_[adjacent].next;
    int acrossPrev = edges_[across].prev, acrossNext = edges_[across].next;
    // The two faces may share several consecutive edges.
    for (int guard = 0; twinFace(adjacentPrev) == other; ++guard) {
      if (guard > faces_[f].vertexCount) {
        internalError("a face surrounds another");
      }
      adjacentPrev = edges_[adjacentPrev].prev;
      acrossNext = edges_[acrossNext].next;
    }
    for (int guard = 0; twinFace(adjacentNext) == other; ++guard) {
      if (guard > faces_[f].vertexCount) {
        internalError("a face surrounds another");
      }
      acrossPrev = edges_[acrossPrev].prev;
      adjacentNext = edges_[adjacentNext].next;
    }
    for (int e = edges_[adjacentPrev].next; e != adjacentNext; e = edges_[e].next) {
      deadEdges_.push_back(e);
      deadEdges_.push_back(edges_[e].twin);
    }
    for (int e = acrossNext, guard = 0; e != edges_[acrossPrev].next; e = edges_[e].next) {
      if (++guard > faces_[other].vertexCount) {
        internalError("an open edge loop");
      }
      edges_[e].face = f;
    }
    faces_[f].edge = adjacentNext;
    const int gone1 = connect(f, acrossPrev, adjacentNext);
    const int gone2 = connect(f, adjacentPrev, acrossNext);
    computePlane(f);
    checkFace(f);
    movePoints(other, f);
    for (int gone : {gone1, gone2}) {
      if (gone >= 0) {
        movePoints(gone, f);
      }
    }
  }

  void checkFace(int f) const {
    if (faces_[f].vertexCount < 3) {
      internalError("a face with fewer than three vertices");
    }
    int e = faces_[f].edge;
    do {
      const int t = edges_[e].twin;
      if (edges_[e].face != f || edges_[t].twin != e || edges_[t].face == f ||
          faces_[edges_[t].face].mark != Mark::Active || edges_[t].head != tail(e)) {
        internalError("broken adjacency");
      }
      e = edges_[e].next;
    } while (e != faces_[f].edge);
  }

  /// The face across the third edge of the triangle that a merge would reduce to an edge where
  /// edges @p a and @p b meet (both bordering it), -1 when none would.
  int collapseTarget(int a, int b, int& triangle) const {
    triangle = twinFace(a);
    if (triangle != twinFace(b) || faces_[triangle].vertexCount != 3) {
      triangle = -1;
      return -1;
    }
    int third = faces_[triangle].edge;
    while (third == edges_[a].twin || third == edges_[b].twin) {
      third = edges_[third].next;
    }
    return twinFace(third);
  }

  /// False when merging face @p f with the face across its edge @p e would break the mesh: the
  /// two touch at a vertex away from their common edges (the merged polygon would pass twice
  /// through it), or a triangle beside them would shrink to an edge next to another face that
  /// goes. Such merges are left out; the faces stay apart, slightly bent.
  bool mergeKeepsSimple(int f, int e) {
    ++stamp_;
    int x = faces_[f].edge;
    do {
      mark_[static_cast<std::size_t>(edges_[x].head)] = stamp_;
      x = edges_[x].next;
    } while (x != faces_[f].edge);
    const int other = twinFace(e);
    const int limit = faces_[other].vertexCount;
    // The other face's run of edges along f, then its vertices off the run.
    int first = edges_[e].twin, last = first;
    for (int guard = 0; twinFace(edges_[first].prev) == f; ++guard) {
      if (guard > limit) {
        return false;
      }
      first = edges_[first].prev;
    }
    for (int guard = 0; twinFace(edges_[last].next) == f; ++guard) {
      if (guard > limit) {
        return false;
      }
      last = edges_[last].next;
    }
    for (int y = edges_[last].next, guard = 0; y != edges_[first].prev; y = edges_[y].next) {
      if (++guard > limit || mark_[static_cast<std::size_t>(edges_[y].head)] == stamp_) {
        return false;
      }
    }
    // The edges meeting at the two ends of the run: f's before and after it, the other's.
    const int fBefore = edges_[edges_[last].twin].prev, fAfter = edges_[edges_[first].twin].next;
    const bool junction1 = twinFace(edges_[first].prev) == twinFace(fAfter);
    const bool junction2 = twinFace(fBefore) == twinFace(edges_[last].next);
    if ((junction1 || junction2) &&
        (edges_[first].prev == edges_[last].next || fBefore == fAfter)) {
      return false;  // one edge left on a side: both ends would rewire the same edge
    }
    int t1, t2;
    const int x1 = collapseTarget(edges_[first].prev, fAfter, t1);
    const int x2 = collapseTarget(fBefore, edges_[last].next, t2);
    for (int target : {x1, x2}) {
      if (target >= 0 && (target == f || target == other || target == t1 || target == t2)) {
        return false;
      }
    }
    return !(t1 >= 0 && t1 == t2);
  }

  /// One merge of face @p f with a neighbour that is coplanar or bends outwards, judged by the
  /// plane of the larger of the two (first pass) or by either (second pass). False when none.
  bool mergeOnce(int f, bool byLargerFace) {
    int e = faces_[f].edge;
    bool convex = true;
    do {
      const int t = edges_[e].twin;
      const int other = edges_[t].face;
      bool merge = false;
      if (!byLargerFace) {
        merge = oppositeCentroidDistance(e) > -tol_ || oppositeCentroidDistance(t) > -tol_;
      } else {
        const bool fLarger = faces_[f].area > faces_[other].area;
        const int judge = fLarger ? e : t;  // the edge on the larger face
        const int other2 = fLarger ? t : e;
        if (oppositeCentroidDistance(judge) > -tol_) {
          merge = true;
        } else if (oppositeCentroidDistance(other2) > -tol_) {
          convex = false;
        }
      }
      if (merge && mergeKeepsSimple(f, e)) {
        mergeFaces(f, e);
        return true;
      }
      e = edges_[e].next;
    } while (e != faces_[f].edge);
    if (!convex) {
      faces_[f].nonConvex = true;
    }
    return false;
  }

  void addPoint(int eye, int f) {
    horizon_.clear();
    visible_.clear();
    newFaces_.clear();
    unclaimed_.clear();
    deadEdges_.clear();
    deadFaces_.clear();
    computeHorizon(eye, f);
    const std::size_t n = horizon_.size();
    if (n < 3) {
      internalError("a horizon of fewer than three edges");
    }
    for (int e : horizon_) {
      const int g = addTriangle(eye, tail(e), edges_[e].head);
      const int base = edges_[faces_[g].edge].next;  // tail(e) -> head(e)
      edges_[base].twin = edges_[e].twin;
      edges_[edges_[e].twin].twin = base;
      newFaces_.push_back(g);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const int in = edges_[faces_[newFaces_[i]].edge].prev;  // head(e_i) -> eye
      const int out = faces_[newFaces_[(i + 1) % n]].edge;    // eye -> tail(e_i+1)
      if (tail(in) != edges_[out].head) {
        internalError("a horizon that is not one loop");
      }
      edges_[in].twin = out;
      edges_[out].twin = in;
    }
    for (int g : newFaces_) {
      while (faces_[g].mark == Mark::Active && mergeOnce(g, true)) {
      }
    }
    for (int g : newFaces_) {
      if (faces_[g].mark == Mark::Active && faces_[g].nonConvex) {
        faces_[g].nonConvex = false;
        while (faces_[g].mark == Mark::Active && mergeOnce(g, false)) {
        }
      }
    }
    for (int q : unclaimed_) {
      int best = -1;
      double bestDistance = tol_;
      for (int g : newFaces_) {
        if (faces_[g].mark != Mark::Active) {
          continue;
        }
        const double d = distance(g, p_[q]);
        if (d > bestDistance) {
          bestDistance = d;
          best = g;
        }
      }
      if (best >= 0) {
        addOutside(q, best);
      }
    }
    recycle();
  }

  /// Returns the slots of the faces and edges that went to the free lists.
  void recycle() {
    for (int v : visible_) {
      int e = faces_[v].edge;
      for (int i = 0; i < faces_[v].vertexCount; ++i) {
        const int next = edges_[e].next;
        deadEdges_.push_back(e);
        e = next;
      }
      faces_[v].mark = Mark::Deleted;
      deadFaces_.push_back(v);
    }
    for (int e : deadEdges_) {
      if (edges_[e].face >= 0) {
        edges_[e].face = -1;
        freeEdges_.push_back(e);
      }
    }
    for (int f : deadFaces_) {
      faces_[f].outside = -1;
      freeFaces_.push_back(f);
    }
  }

  ConvexHull output() const {
    std::vector<int> index(faces_.size(), -1);
    int count = 0;
    std::size_t corners = 0;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (faces_[f].mark == Mark::Active) {
        index[f] = count++;
        corners += static_cast<std::size_t>(faces_[f].vertexCount);
      }
    }
    ConvexHull hull;
    hull.tolerance = tol_;
    hull.start.reserve(static_cast<std::size_t>(count) + 1);
    hull.normals.reserve(static_cast<std::size_t>(count));
    hull.vertices.reserve(corners);
    hull.neighbours.reserve(corners);
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (index[f] < 0) {
        continue;
      }
      int e = faces_[f].edge;
      const Eigen::Vector3d& origin = p_[tail(e)];
      Eigen::Vector3d twiceArea = Eigen::Vector3d::Zero();
      do {
        hull.vertices.push_back(tail(e));
        hull.neighbours.push_back(index[static_cast<std::size_t>(twinFace(e))]);
        twiceArea += (p_[tail(e)] - origin).cross(p_[edges_[e].head] - origin);
        e = edges_[e].next;
      } while (e != faces_[f].edge);
      hull.start.push_back(static_cast<int>(hull.vertices.size()));
      const double norm = twiceArea.norm();
      hull.normals.push_back(norm > 0.0 ? Eigen::Vector3d(twiceArea / norm) : faces_[f].normal);
    }
    return hull;
  }

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
  std::vector<int> mark_;     ///< per point: stamp_ when on the face mergeKeepsSimple looks at
  int stamp_ = 0;
  std::vector<int> horizon_, visible_, newFaces_, unclaimed_, deadEdges_, deadFaces_;
};

ConvexHull hullWithTolerance(const std::vector<Eigen::Vector3d>& points, double tol,
                             const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                             const int* loIndex, const int* hiIndex) {
  const std::size_t n = points.size();
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int v0 = loIndex[axis], v1 = hiIndex[axis];
  if (hi[axis] - lo[axis] <= tol) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points are at one place, they span no volume");
  }
  const Eigen::Vector3d u = (points[v1] - points[v0]).normalized();
  int v2 = -1;
  double best = tol;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (points[i] - points[v0]).cross(u).norm();
    if (d > best) {
      best = d;
      v2 = static_cast<int>(i);
    }
  }
  if (v2 < 0) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points lie on a line, they span no volume");
  }
  const Eigen::Vector3d normal =
      (points[v1] - points[v0]).cross(points[v2] - points[v0]).normalized();
  int v3 = -1;
  best = tol;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::abs(normal.dot(points[i] - points[v0]));
    if (d > best) {
      best = d;
      v3 = static_cast<int>(i);
    }
  }
  if (v3 < 0) {
    throw std::invalid_argument("convex hull: all " + std::to_string(n) +
                                " points lie on a plane, they span no volume");
  }
  return HullBuilder(points, tol).build(v0, v1, v2, v3);
}

}  // namespace

ConvexHull convexHull(const std::vector<Eigen::Vector3d>& points) {
  const std::size_t n = points.size();
  if (n > kMaxHullPoints) {
    throw std::invalid_argument("convex hull: " + std::to_string(n) + " points, at most " +
                                std::to_string(kMaxHullPoints) + " are taken");
  }
  if (n < 4) {
    throw std::invalid_argument("convex hull: " + std::to_string(n) +
                                " points span no volume (at least four are needed)");
  }
  Eigen::Vector3d lo = points[0], hi = points[0];
  int loIndex[3] = {0, 0, 0}, hiIndex[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    if (!points[i].allFinite()) {
      throw std::invalid_argument("convex hull: point " + std::to_string(i) + " is not finite");
    }
    for (int k = 0; k < 3; ++k) {
      if (points[i][k] < lo[k]) {
        lo[k] = points[i][k];
        loIndex[k] = static_cast<int>(i);
      }
      if (points[i][k] > hi[k]) {
        hi[k] = points[i][k];
        hiIndex[k] = static_cast<int>(i);
      }
    }
  }
  const double magnitude = lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).sum();
  const double tol = std::max(3.0 * std::numeric_limits<double>::epsilon() * magnitude,
                              kRelativeTolerance * (hi - lo).norm());
  // Nearly coplanar points can defeat the merges' bookkeeping; a coarser tolerance merges them
  // earlier and more boldly. Never seen in tests; a safety net.
  for (int attempt = 0;; ++attempt) {
    try {
      return hullWithTolerance(points, tol * std::pow(kRetryFactor, attempt), lo, hi, loIndex,
                               hiIndex);
    } catch (const InternalError& e) {
      if (attempt == 2) {
        throw std::invalid_argument(std::string("convex hull: internal inconsistency (") +
                                    e.what() + ") with " + std::to_string(n) + " points");
      }
    }
  }
}

void hullVolume(const ConvexHull& hull, const std::vector<Eigen::Vector3d>& points, double& volume,
                Eigen::Vector3d& centroid, Eigen::Matrix3d* spread) {
  // Tetrahedra from a point inside (the mean of the vertices): no cancellation of large terms.
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (int v : hull.vertices) {
    reference += points[static_cast<std::size_t>(v)];
  }
  reference /= static_cast<double>(std::max<std::size_t>(hull.vertices.size(), 1));
  volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // about the reference point
  for (std::size_t f = 0; f < hull.faceCount(); ++f) {
    const int* corner = hull.vertices.data() + hull.start[f];
    const Eigen::Vector3d a = points[static_cast<std::size_t>(corner[0])] - reference;
    for (int i = 1; i + 1 < hull.cornerCount(f); ++i) {
      const Eigen::Vector3d b = points[static_cast<std::size_t>(corner[i])] - reference;
      const Eigen::Vector3d c = points[static_cast<std::size_t>(corner[i + 1])] - reference;
      const double v = a.dot(b.cross(c)) / 6.0;
      volume += v;
      moment += v * (a + b + c) / 4.0;
      if (spread) {  // a tetrahedron with a corner at the origin: v/20 (sum p p^T + s s^T)
        const Eigen::Vector3d s = a + b + c;
        second += v / 20.0 *
                  (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
      }
    }
  }
  const Eigen::Vector3d offset =
      volume > 0.0 ? Eigen::Vector3d(moment / volume) : Eigen::Vector3d::Zero();
  centroid = reference + offset;
  if (spread) {
    *spread = second - volume * offset * offset.transpose();
  }
}

}  // namespace placement_samplers::detail
