#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "placement_samplers/sampling/random.hpp"

namespace placement_samplers {

struct PlacedEntry;

/// One item of a uniform sampler's `relations:` list (README, "Relations").
struct Relation {
  enum class Kind { NextTo, AwayFrom, AlignWith, Face };
  /// The 90-degree sector around the target's +y (left), -y, +x (front) or -x (back), in its
  /// own frame (REP 103); Any: no sector.
  enum class Side { Any, Left, Right, Front, Back };
  Kind kind = Kind::NextTo;
  std::string target;  ///< a fixture or an object placed before the related object
  Side side = Side::Any;
  /// NextTo: the gap's [min, max]; AwayFrom: [distance, inf] [m]. The gap is the centre
  /// distance in x-y minus both horizontal radii.
  double minGap = 0.0;
  double maxGap = 0.0;
  double tolerance = 0.0;            ///< AlignWith, Face [rad]
  double period = 2 * M_PI;          ///< AlignWith: the yaw is compared modulo this (0, 2 pi] [rad]
  std::vector<std::string> objects;  ///< the objects it applies to; empty: all of the sampler's
  bool requestFixture = false;       ///< the target is a fixture every request gives

  bool isPosition() const { return kind == Kind::NextTo || kind == Kind::AwayFrom; }
  /// True when it applies to @p object (by name).
  bool appliesTo(const std::string& object) const;
};

/// Relations a sampler may have (each object is tested against all that apply to it).
constexpr std::size_t kMaxRelations = 16;
/// The attempt before which a position relation that cannot hold anywhere in the region's box
/// fails the object (infeasibleReason()): late enough that a relation that holds somewhere
/// usually never pays for the test, early enough to fail at once.
constexpr std::uint32_t kRelationProbeAttempts = 64;

/// "next_to", "away_from", "align_with" or "face".
const char* relationKindName(Relation::Kind kind);
/// "any", "left", "right", "front" or "back".
const char* relationSideName(Relation::Side side);
/// `relations[i] (next_to 'plate', side left, gap [0.02, 0.06] m)`: how messages name it.
std::string relationLabel(const Relation& relation, std::size_t index);

/// The heading of @p orientation: the angle of its +x axis projected on the x-y plane [rad];
/// 0 when that axis is vertical.
double headingOf(const Eigen::Quaterniond& orientation);
/// |a - b| modulo @p period, in [0, period / 2] [rad].
double angleApart(double a, double b, double period);

/// A target as the relations see it: its x-y centre, heading and horizontal radius.
struct RelationTarget {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< [m]
  double cosHeading = 1.0;
  double sinHeading = 0.0;
  double heading = 0.0;  ///< [rad]
  double radius = 0.0;   ///< [m]
};
/// @p withHeading false leaves `heading` 0 (its cosine and sine are set): the position tests do
/// not need it.
RelationTarget relationTarget(const PlacedEntry& entry, bool withHeading = true);

/// True when @p local (a point in the target's frame, relative to its centre) is in @p side's
/// sector; the sector's edges belong to it.
inline bool inSide(Relation::Side side, double x, double y) {
  switch (side) {
    case Relation::Side::Any:
      return true;
    case Relation::Side::Left:
      return y >= std::abs(x);
    case Relation::Side::Right:
      return -y >= std::abs(x);
    case Relation::Side::Front:
      return x >= std::abs(y);
    case Relation::Side::Back:
      return -x >= std::abs(y);
  }
  return true;
}

/// One position relation (next_to, away_from) against a resolved target. Sampling and
/// validation decide with the same holds(), bit for bit.
struct PositionTest {
  // No default member initialisers: an object's array of them is left unset but for its first
  // `count` (PlacementRelations).
  Eigen::Vector2d centre;
  double cosHeading;
  double sinHeading;
  double low;            ///< minimum gap plus the target's radius [m]
  double high;           ///< maximum gap plus the target's radius (inf: none) [m]
  double targetRadius;   ///< [m]
  double minGap;         ///< the relation's [m]
  double maxGap;         ///< the relation's (inf: away_from) [m]
  std::ptrdiff_t entry;  ///< the target's index in the scene's entries (-1: not known)
  Relation::Side side;
  std::uint16_t index;  ///< in the sampler's relations

  PositionTest() = default;
  PositionTest(const Relation& relation, std::size_t index, const RelationTarget& target);

  /// True when an object of horizontal radius @p radius centred at @p p satisfies it.
  bool holds(const Eigen::Vector2d& p, double radius) const {
    const Eigen::Vector2d d = p - centre;
    const double lo = low + radius;
    const double hi = high + radius;
    const double dd = d.squaredNorm();
    if ((lo > 0.0 && dd < lo * lo) || dd > hi * hi) {
      return false;
    }
    return inSector(p);
  }
  /// The fcl modes' test: the side by the centres, the gap given (the shapes' signed distance).
  bool holdsGap(const Eigen::Vector2d& p, double gap) const {
    return gap >= minGap && gap <= maxGap && inSector(p);
  }
  /// True when @p p is on the relation's side of the target (always for any).
  bool inSector(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - centre;
    return side == Relation::Side::Any || inSide(side, d.x() * cosHeading + d.y() * sinHeading,
                                                 d.y() * cosHeading - d.x() * sinHeading);
  }
  /// The gap between the disks [m] (for messages).
  double gap(const Eigen::Vector2d& p, double radius) const {
    return (p - centre).norm() - radius - targetRadius;
  }
};

/// Why no centre in the box @p lo .. @p hi (world, [m]) can satisfy @p test for an object of
/// a horizontal radius in [@p least, @p most] [m]; "" when some may (shapes and keep-out zones
/// inside the box are not looked at: it only fails what cannot hold).
std::string infeasibleReason(const PositionTest& test, double least, double most,
                             const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

/// Rounding a sampled yaw may carry through its quaternion: the slack of the angle tests of
/// align_with and face outside sampling (validation, display) [rad].
constexpr double kRelationAngleSlack = 1e-9;

/// How far the yaw of an object at @p p with @p orientation is from what align_with or face
/// wants of it against @p target [rad] (modulo the relation's period; face: 2 pi).
double relationAngleError(const Relation& relation, const RelationTarget& target,
                          const Eigen::Vector2d& p, const Eigen::Quaterniond& orientation);

/// True when @p relation holds for an object of horizontal radius @p radius [m] at @p p with
/// @p orientation, against @p target: PositionTest::holds() for next_to and away_from, the yaw
/// within the tolerance (plus kRelationAngleSlack) for align_with and face.
bool relationHolds(const Relation& relation, const RelationTarget& target, const Eigen::Vector2d& p,
                   double radius, const Eigen::Quaterniond& orientation);

/// The allowed turns of a rotation relation for one placement: the turn a about the sampler's
/// z axis gives the object the heading a + h0 (h0: the heading of its initial orientation).
struct RotationTest {
  Relation::Kind kind = Relation::Kind::AlignWith;
  std::uint16_t index = 0;
  double tolerance = 0.0;  ///< [rad]
  double period = 2 * M_PI;
  double centre = 0.0;                               ///< AlignWith: target heading - h0
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< Face: the target's centre
  double h0 = 0.0;                                   ///< [rad]
};

/// The turns within [low, high] that align_with allows: centre + k period +- tolerance for
/// every integer k, clipped to [low, high]. Their total length [rad].
double alignedLength(const RotationTest& test, double low, double high);
/// The turn at @p u in [0, alignedLength()) along the allowed turns in increasing order.
double alignedTurn(const RotationTest& test, double low, double high, double u);

/// The relations of one object in one scene, resolved against their targets, and the attempts
/// each position relation refused.
struct PlacementRelations {
  std::array<PositionTest, kMaxRelations> position;
  std::array<std::uint32_t, kMaxRelations> refused{};
  std::size_t count = 0;  ///< position tests
  bool turns = false;     ///< @ref turn sets the yaw
  RotationTest turn;
  double alignedLength = 0.0;  ///< align_with: the allowed turns' length [rad]
  /// The fcl modes: the gaps are the shapes' exact distances (CollisionChecker::exactDistance()),
  /// the orientation drawn before the test.
  bool exact = false;
  /// The box the centres are drawn from (world) for infeasibleReason(); lo > hi: not known.
  Eigen::Vector2d boxLo = Eigen::Vector2d::Ones();
  Eigen::Vector2d boxHi = Eigen::Vector2d::Zero();
  double leastRadius = 0.0;  ///< the object's horizontal radius (its smallest pose's) [m]
  double mostRadius = 0.0;   ///< and largest [m]

  /// True when every position relation holds; counts the first that does not.
  bool holds(const Eigen::Vector2d& p, double radius) {
    for (std::size_t i = 0; i < count; ++i) {
      if (!position[i].holds(p, radius)) {
        ++refused[i];
        return false;
      }
    }
    return true;
  }
};

}  // namespace placement_samplers
