#include <Eigen/Geometry>
#include <algorithm>
#include <initializer_list>

#include "geometry/hull_builder.hpp"

namespace placement_samplers::detail {

int HullBuilder::connect(int f, int prev, int e) {
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

void HullBuilder::mergeFaces(int f, int adjacent) {
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

void HullBuilder::checkFace(int f) const {
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

int HullBuilder::collapseTarget(int a, int b, int& triangle) const {
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

bool HullBuilder::mergeKeepsSimple(int f, int e) {
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
  if ((junction1 || junction2) && (edges_[first].prev == edges_[last].next || fBefore == fAfter)) {
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

bool HullBuilder::mergeOnce(int f, bool byLargerFace) {
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

}  // namespace placement_samplers::detail
