#include "validation/overlap_search.hpp"

#include "placement_samplers/text.hpp"
#include "validation/verdict_text.hpp"

namespace placement_samplers {
namespace detail {

OverlapSearch::OverlapSearch(CollisionMode mode, double margin, const ValidationOptions& options)
    : mode_(mode),
      margin_(margin),
      options_(options),
      checker_(makeCollisionChecker(mode, margin)) {}

void OverlapSearch::list(ObjectVerdict& verdict, const Candidate& candidate,
                         const std::string& name, const std::string& sampler, std::ptrdiff_t hit,
                         const std::vector<PlacedEntry>& entries) {
  const char* mode = collisionModeName(mode_);
  const auto listOne = [&](const PlacedEntry& entry) {
    addViolation(verdict, Violation::Kind::Overlap, sampler, std::string(entry.name), 0.0,
                 "object " + quoteText(name) + " overlaps " +
                     (entry.fixture ? "fixture " : "object ") + quoteText(entry.name) +
                     " under the " + mode + " check");
    verdict.reasons.back().check = mode;
  };
  std::size_t listed = 0;
  std::size_t more = 0;
  bool cut = false;
  for (const PlacedEntry& entry : entries) {
    if (tests_ >= options_.maxOverlapTests) {
      cut = true;
      break;
    }
    ++tests_;
    if (!pairCollides(entry, candidate, entries)) {
      continue;
    }
    if (listed == options_.maxOverlapsListed) {
      ++more;
      continue;
    }
    ++listed;
    listOne(entry);
  }
  if (cut && listed == 0 && options_.maxOverlapsListed > 0) {
    listOne(entries[static_cast<std::size_t>(hit)]);  // not reached by the search
    ++listed;
  }
  const std::string stopped = "the scene's overlap search stopped after " +
                              std::to_string(options_.maxOverlapTests) + " tests";
  const std::string count = std::to_string(more);
  const char* kinds = more == 1 ? " fixture or object" : " fixtures and objects";
  if (listed > 0 && (more > 0 || cut)) {
    std::string note = more > 0 ? count + " more" + kinds + ", not listed" : "";
    if (cut) {
      note += std::string(more > 0 ? "; " : "") + "possibly others: " + stopped;
    }
    verdict.reasons.back().message += " (and " + note + ")";
  } else if (listed == 0 && (more > 0 || cut)) {
    addViolation(verdict, Violation::Kind::Overlap, sampler, "", 0.0,
                 "object " + quoteText(name) + " overlaps " +
                     (more == 0 ? std::string("fixtures or objects")
                                : (cut ? "at least " : "") + count + kinds) +
                     " under the " + mode + " check (not listed" + (cut ? "; " + stopped : "") +
                     ")");
    verdict.reasons.back().check = mode;
  }
}

bool OverlapSearch::pairCollides(const PlacedEntry& entry, const Candidate& candidate,
                                 const std::vector<PlacedEntry>& entries) {
  // A checker keeps what it learnt of each object (FCL geometry) and visits it all when
  // cleared, so a fresh one is taken every kPairObjects objects: a pair test then costs the
  // same in a scene of any size.
  constexpr std::size_t kPairObjects = 64;
  seen_.insert(entry.object);
  seen_.insert(candidate.object);
  if (seen_.size() > kPairObjects) {
    checker_ = makeCollisionChecker(mode_, margin_);
    seen_ = {entry.object, candidate.object};
  }
  one_[0] = entry;
  // The candidate's support is the one entry here when it is this one.
  Candidate pair = candidate;
  pair.support =
      candidate.support >= 0 && &entry == &entries[static_cast<std::size_t>(candidate.support)]
          ? 0
          : -1;
  checker_->clear();
  checker_->added(one_, 0);
  return checker_->firstCollision(one_, pair) != CollisionChecker::kNone;
}

}  // namespace detail
}  // namespace placement_samplers
