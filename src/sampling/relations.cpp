// Relations between objects (README, "Relations"): the tests sampling and validation share.
#include "placement_samplers/sampling/relations.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>

#include "placement_samplers/collision/collision_checker.hpp"
#include "placement_samplers/text.hpp"

namespace placement_samplers {

bool Relation::appliesTo(const std::string& object) const {
  if (objects.empty()) {
    return object != target;
  }
  return std::find(objects.begin(), objects.end(), object) != objects.end();
}

const char* relationKindName(Relation::Kind kind) {
  switch (kind) {
    case Relation::Kind::NextTo:
      return "next_to";
    case Relation::Kind::AwayFrom:
      return "away_from";
    case Relation::Kind::AlignWith:
      return "align_with";
    case Relation::Kind::Face:
      return "face";
  }
  return "next_to";
}

const char* relationSideName(Relation::Side side) {
  switch (side) {
    case Relation::Side::Any:
      return "any";
    case Relation::Side::Left:
      return "left";
    case Relation::Side::Right:
      return "right";
    case Relation::Side::Front:
      return "front";
    case Relation::Side::Back:
      return "back";
  }
  return "any";
}

std::string relationLabel(const Relation& relation, std::size_t index) {
  std::ostringstream out;
  out << "relations[" << index << "] (" << relationKindName(relation.kind) << " "
      << quoteText(relation.target);
  switch (relation.kind) {
    case Relation::Kind::NextTo:
      if (relation.side != Relation::Side::Any) {
        out << ", side " << relationSideName(relation.side);
      }
      out << ", gap [" << relation.minGap << ", " << relation.maxGap << "] m";
      break;
    case Relation::Kind::AwayFrom:
      out << ", gap >= " << relation.minGap << " m";
      break;
    case Relation::Kind::AlignWith:
      out << ", tolerance " << relation.tolerance << " rad, period " << relation.period << " rad";
      break;
    case Relation::Kind::Face:
      out << ", tolerance " << relation.tolerance << " rad";
      break;
  }
  out << ")";
  return out.str();
}

double headingOf(const Eigen::Quaterniond& orientation) {
  const Eigen::Vector3d x = orientation * Eigen::Vector3d::UnitX();
  if (std::sqrt(x.x() * x.x() + x.y() * x.y()) < 1e-9) {
    return 0.0;
  }
  return std::atan2(x.y(), x.x());
}

double angleApart(double a, double b, double period) {
  double d = std::fmod(std::abs(a - b), period);
  return std::min(d, period - d);
}

RelationTarget relationTarget(const PlacedEntry& entry, bool withHeading) {
  RelationTarget t;
  t.centre = entry.position.head<2>();
  // The heading's cosine and sine straight from the +x axis: no trigonometry but atan2.
  const Eigen::Vector3d x = entry.orientation * Eigen::Vector3d::UnitX();
  const double h = std::sqrt(x.x() * x.x() + x.y() * x.y());
  if (h >= 1e-9) {
    t.cosHeading = x.x() / h;
    t.sinHeading = x.y() / h;
    t.heading = withHeading ? std::atan2(x.y(), x.x()) : 0.0;
  }
  t.radius = entry.object->horizontalRadius;
  return t;
}

PositionTest::PositionTest(const Relation& relation, std::size_t i, const RelationTarget& target)
    : centre(target.centre),
      cosHeading(target.cosHeading),
      sinHeading(target.sinHeading),
      low(relation.minGap + target.radius),
      high(relation.kind == Relation::Kind::AwayFrom ? std::numeric_limits<double>::infinity()
                                                     : relation.maxGap + target.radius),
      targetRadius(target.radius),
      minGap(relation.minGap),
      maxGap(relation.kind == Relation::Kind::AwayFrom ? std::numeric_limits<double>::infinity()
                                                       : relation.maxGap),
      entry(-1),
      side(relation.side),
      index(static_cast<std::uint16_t>(i)) {}

bool relationHolds(const Relation& relation, const RelationTarget& target, const Eigen::Vector2d& p,
                   double radius, const Eigen::Quaterniond& orientation) {
  if (relation.isPosition()) {
    return PositionTest(relation, 0, target).holds(p, radius);
  }
  return relationAngleError(relation, target, p, orientation) <=
         relation.tolerance + kRelationAngleSlack;
}

double relationAngleError(const Relation& relation, const RelationTarget& target,
                          const Eigen::Vector2d& p, const Eigen::Quaterniond& orientation) {
  if (relation.kind == Relation::Kind::Face) {
    const Eigen::Vector2d d = target.centre - p;
    return angleApart(headingOf(orientation), std::atan2(d.y(), d.x()), 2 * M_PI);
  }
  return angleApart(headingOf(orientation), target.heading, relation.period);
}

namespace {

/// A convex polygon of at most 8 vertices (a box cut by two half-planes has at most 6), on the
/// stack: the test runs once per object and scene.
struct Polygon {
  std::array<Eigen::Vector2d, 8> v;
  std::size_t n = 0;
};

/// The part of @p poly where n . p >= 0 (Sutherland-Hodgman, one edge).
Polygon clip(const Polygon& poly, const Eigen::Vector2d& n) {
  Polygon out;
  for (std::size_t i = 0; i < poly.n; ++i) {
    const Eigen::Vector2d& a = poly.v[i];
    const Eigen::Vector2d& b = poly.v[(i + 1) % poly.n];
    const double da = n.dot(a);
    const double db = n.dot(b);
    if (da >= 0.0) {
      out.v[out.n++] = a;
    }
    if ((da >= 0.0) != (db >= 0.0)) {
      out.v[out.n++] = a + (b - a) * (da / (da - db));
    }
  }
  return out;
}

double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len = ab.squaredNorm();
  const double t = len > 0.0 ? std::clamp(-a.dot(ab) / len, 0.0, 1.0) : 0.0;
  return (a + t * ab).norm();
}

}  // namespace

std::string infeasibleReason(const PositionTest& test, double least, double most,
                             const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  // The box relative to the target's centre, cut to the side's sector (u . d >= |v . d|).
  Polygon poly;
  poly.v[0] = Eigen::Vector2d(lo.x(), lo.y()) - test.centre;
  poly.v[1] = Eigen::Vector2d(hi.x(), lo.y()) - test.centre;
  poly.v[2] = Eigen::Vector2d(hi.x(), hi.y()) - test.centre;
  poly.v[3] = Eigen::Vector2d(lo.x(), hi.y()) - test.centre;
  poly.n = 4;
  const Eigen::Vector2d front(test.cosHeading, test.sinHeading);
  const Eigen::Vector2d left(-test.sinHeading, test.cosHeading);
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  switch (test.side) {
    case Relation::Side::Any:
      break;
    case Relation::Side::Left:
      u = left;
      break;
    case Relation::Side::Right:
      u = -left;
      break;
    case Relation::Side::Front:
      u = front;
      break;
    case Relation::Side::Back:
      u = -front;
      break;
  }
  constexpr double kSlack = 1e-9;  // [m]: rounding must not make a feasible relation fail
  if (test.side != Relation::Side::Any) {
    const Eigen::Vector2d v(-u.y(), u.x());
    poly = clip(clip(poly, u - v), u + v);
    if (poly.n == 0) {
      return std::string("no position of its region is on the ") + relationSideName(test.side) +
             " of the target";
    }
  }
  // Squared distances first (no root): most relations are feasible at a glance.
  const double lowR = test.low + least;
  const double highR = test.high + most;
  double far2 = 0.0;
  bool reached = false;  // some vertex within highR
  for (std::size_t i = 0; i < poly.n; ++i) {
    const double d2 = poly.v[i].squaredNorm();
    far2 = std::max(far2, d2);
    reached = reached || d2 <= (highR + kSlack) * (highR + kSlack);
  }
  const bool tooNear = lowR - kSlack > 0.0 && far2 < (lowR - kSlack) * (lowR - kSlack);
  if (!tooNear && reached) {
    return "";
  }
  double near = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (std::size_t i = 0; i < poly.n; ++i) {
    const Eigen::Vector2d& a = poly.v[i];
    const Eigen::Vector2d& b = poly.v[(i + 1) % poly.n];
    near = std::min(near, segmentDistance(a, b));
    // Counter-clockwise polygon: the origin is inside when it is left of every edge.
    inside = inside && (a.x() * b.y() - a.y() * b.x()) >= 0.0;
  }
  if (inside) {
    near = 0.0;
  }
  const double far = std::sqrt(far2);
  if (!tooNear && near <= highR + kSlack) {
    return "";
  }
  std::ostringstream out;
  if (far < lowR - kSlack) {
    out << "its region's positions" << (test.side != Relation::Side::Any ? " on that side" : "")
        << " are at most " << far << " m from the target's centre, the relation needs at least "
        << lowR << " m";
    return out.str();
  }
  out << "its region's positions" << (test.side != Relation::Side::Any ? " on that side" : "")
      << " are at least " << near << " m from the target's centre, the relation needs at most "
      << highR << " m";
  return out.str();
}

double alignedLength(const RotationTest& t, double low, double high) {
  const double w = 2.0 * t.tolerance;
  if (w >= t.period) {
    return high - low;
  }
  const double kmin = std::ceil((low - t.tolerance - t.centre) / t.period);
  const double kmax = std::floor((high + t.tolerance - t.centre) / t.period);
  if (kmax < kmin) {
    return 0.0;
  }
  const auto piece = [&](double k) {
    const double c = t.centre + k * t.period;
    return std::max(0.0, std::min(high, c + t.tolerance) - std::max(low, c - t.tolerance));
  };
  if (kmax == kmin) {
    return piece(kmin);
  }
  return piece(kmin) + piece(kmax) + (kmax - kmin - 1.0) * w;
}

double alignedTurn(const RotationTest& t, double low, double high, double u) {
  const double w = 2.0 * t.tolerance;
  if (w >= t.period) {
    return low + u;
  }
  const double kmin = std::ceil((low - t.tolerance - t.centre) / t.period);
  const double kmax = std::floor((high + t.tolerance - t.centre) / t.period);
  const auto start = [&](double k) { return std::max(low, t.centre + k * t.period - t.tolerance); };
  const auto piece = [&](double k) {
    const double c = t.centre + k * t.period;
    return std::max(0.0, std::min(high, c + t.tolerance) - std::max(low, c - t.tolerance));
  };
  const double first = piece(kmin);
  if (u < first || kmax == kmin) {
    return std::min(start(kmin) + u, high);
  }
  u -= first;
  const double full = std::floor(u / w);
  if (kmin + 1.0 + full < kmax) {
    return start(kmin + 1.0 + full) + (u - full * w);
  }
  return std::min(start(kmax) + (u - (kmax - kmin - 1.0) * w), high);
}

}  // namespace placement_samplers
