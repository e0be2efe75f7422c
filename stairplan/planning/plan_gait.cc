#include "stairplan/planning/plan_gait.h"

namespace stairplan {

const char* ToString(Gait gait) {
  switch (gait) {
    case Gait::kCrawl: return "crawl";
    case Gait::kCrawlAlternate: return "crawl_alt";
    case Gait::kTrot: return "trot";
    case Gait::kPaperCrawl: return "paper_crawl";
    case Gait::kPaperCrawlAlternate: return "paper_crawl_alt";
    case Gait::kWalk: return "walk";
  }
  return "unknown";
}

std::optional<Gait> ParseGait(std::string_view text) {
  for (const Gait g : kAllGaits) {
    if (text == ToString(g)) return g;
  }
  return std::nullopt;
}

bool IsQuasiStatic(Gait gait) { return gait != Gait::kTrot; }

bool IsJudgedDynamically(Gait gait) { return gait == Gait::kWalk || gait == Gait::kTrot; }

const char* GaitName(const std::optional<Gait>& gait) { return gait ? ToString(*gait) : ""; }

}  // namespace stairplan
