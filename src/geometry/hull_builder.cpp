#include "geometry/hull_builder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <utility>

namespace placement_samplers::detail {

ConvexHull HullBuilder::build(int v0, int v1, int v2, int v3) {
  // Faces and edges in use stay below twice and six times the points; at most this much is
  // reserved ahead (larger sets grow as needed).
  const std::size_t expected = std::min<std::size_t>(p_.size(), 1 << 17);
  faces_.reserve(2 * expected + 4);
  edges_.reserve(6 * expected + 12);
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

int HullBuilder::newEdge() {
  if (!freeEdges_.empty()) {
    const int e = freeEdges_.back();
    freeEdges_.pop_back();
    return e;
  }
  edges_.emplace_back();
  return static_cast<int>(edges_.size()) - 1;
}

int HullBuilder::newFace() {
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

int HullBuilder::addTriangle(int a, int b, int c) {
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

void HullBuilder::computePlane(int f) {
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

void HullBuilder::addOutside(int q, int f) {
  if (faces_[f].outside < 0) {
    pending_.push_back(f);
  }
  nextOutside_[q] = faces_[f].outside;
  faces_[f].outside = q;
}

void HullBuilder::movePoints(int f, int into) {
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

void HullBuilder::kill(int f) {
  if (faces_[f].mark == Mark::Active) {
    faces_[f].mark = Mark::Deleted;
    deadFaces_.push_back(f);
  }
}

void HullBuilder::initialSimplex(int v0, int v1, int v2, int v3) {
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

void HullBuilder::computeHorizon(int eye, int f) {
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

void HullBuilder::addPoint(int eye, int f) {
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
  // The new faces' planes side by side: every orphaned point is tested against each.
  planes_.clear();
  for (int g : newFaces_) {
    if (faces_[g].mark == Mark::Active) {
      planes_.push_back({faces_[g].normal, faces_[g].offset, g});
    }
  }
  for (int q : unclaimed_) {
    const Eigen::Vector3d& p = p_[q];
    int best = -1;
    double bestDistance = tol_;
    for (const Plane& plane : planes_) {
      const double d = plane.normal.dot(p) - plane.offset;
      if (d > bestDistance) {
        bestDistance = d;
        best = plane.face;
      }
    }
    if (best >= 0) {
      addOutside(q, best);
    }
  }
  recycle();
}

void HullBuilder::recycle() {
  for (int v : visible_) {
    int e = faces_[v].edge;
    for (int i = 0; i < faces_[v].vertexCount; ++i) {
      const int next = edges_[e].next;
      edges_[e].face = -1;
      freeEdges_.push_back(e);
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

ConvexHull HullBuilder::output() const {
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
    do {
      hull.vertices.push_back(tail(e));
      hull.neighbours.push_back(index[static_cast<std::size_t>(twinFace(e))]);
      e = edges_[e].next;
    } while (e != faces_[f].edge);
    hull.start.push_back(static_cast<int>(hull.vertices.size()));
    hull.normals.push_back(faces_[f].normal);  // computePlane's, from the final polygon
  }
  return hull;
}

}  // namespace placement_samplers::detail
