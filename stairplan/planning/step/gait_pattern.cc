#include "stairplan/planning/step/gait_pattern.h"

#include <stdexcept>
#include <string>

namespace stairplan {

const GaitPattern& PatternOf(Gait gait) {
  using R = TravelRole;
  static const GaitPattern kCrawl{4, 1, {{{R::kRearRight, R::kRearRight}, {R::kRearLeft, R::kRearLeft},
                                          {R::kForeRight, R::kForeRight}, {R::kForeLeft, R::kForeLeft}}}};
  static const GaitPattern kCrawlAlternate{4, 1, {{{R::kRearRight, R::kRearRight}, {R::kRearLeft, R::kRearLeft},
                                                   {R::kForeLeft, R::kForeLeft}, {R::kForeRight, R::kForeRight}}}};
  static const GaitPattern kTrot{2, 2, {{{R::kRearRight, R::kForeLeft}, {R::kRearLeft, R::kForeRight},
                                         {R::kRearRight, R::kForeLeft}, {R::kRearLeft, R::kForeRight}}}};
  switch (gait) {
    case Gait::kCrawl:
    case Gait::kWalk: return kCrawl;  // the walk swings in the crawl's order
    case Gait::kCrawlAlternate: return kCrawlAlternate;
    case Gait::kTrot: return kTrot;
    case Gait::kPaperCrawl:
    case Gait::kPaperCrawlAlternate: break;
  }
  throw std::invalid_argument(std::string("gait ") + ToString(gait) +
                              ": the paper's crawls order their swings by their contact offsets, not by a controller's pattern");
}

}  // namespace stairplan
