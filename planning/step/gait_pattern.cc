#include "planning/step/gait_pattern.h"

namespace stairplan {

const char* ToString(Gait gait) {
  switch (gait) {
    case Gait::kCrawl: return "crawl";
    case Gait::kCrawlAlternate: return "crawl_alt";
    case Gait::kTrot: return "trot";
  }
  return "unknown";
}

const GaitPattern& PatternOf(Gait gait) {
  using R = TravelRole;
  static const GaitPattern kCrawl{4, 1, {{{R::kRearRight, R::kRearRight}, {R::kRearLeft, R::kRearLeft},
                                          {R::kForeRight, R::kForeRight}, {R::kForeLeft, R::kForeLeft}}}};
  static const GaitPattern kCrawlAlternate{4, 1, {{{R::kRearRight, R::kRearRight}, {R::kRearLeft, R::kRearLeft},
                                                   {R::kForeLeft, R::kForeLeft}, {R::kForeRight, R::kForeRight}}}};
  static const GaitPattern kTrot{2, 2, {{{R::kRearRight, R::kForeLeft}, {R::kRearLeft, R::kForeRight},
                                         {R::kRearRight, R::kForeLeft}, {R::kRearLeft, R::kForeRight}}}};
  switch (gait) {
    case Gait::kCrawl: return kCrawl;
    case Gait::kCrawlAlternate: return kCrawlAlternate;
    case Gait::kTrot: return kTrot;
  }
  return kCrawl;
}

}  // namespace stairplan
