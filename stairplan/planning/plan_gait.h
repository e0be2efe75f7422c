// The gait a plan walks: one enum for the step planner's controllers, the plans they make, the
// validator that judges them and the files that carry them.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace stairplan {

/// Which legs swing together and in which order. The crawl of Chen, Ko, Li, Lin 2012, "Stair
/// Climbing in a Quadruped Robot": one leg at a time, rear right, rear left, fore right, fore left;
/// its alternative with the fore pair switched; a trot with diagonal pairs. kPaperCrawl and
/// kPaperCrawlAlternate are the same two crawls with the paper's own footholds and timing
/// (stairplan/planning/step/paper_crawl.h). kWalk is a lateral-sequence walk: the crawl's footholds
/// and swing order with brief four-feet phases between the swings (PipelineOptions::
/// walk_shift_duration), about 40 % faster; its body still leans over each support triangle, and
/// the validator's dynamic check judges whether the legs can produce the faster weight shifts. kTrot
/// swings the diagonal pairs together; the pipeline plans it on the crawl's footholds
/// (CrawlSettings::diagonal_pairs), its body's ZMP on the standing diagonal.
enum class Gait { kCrawl, kCrawlAlternate, kTrot, kPaperCrawl, kPaperCrawlAlternate, kWalk };

/// Every gait, in the enum's order.
inline constexpr std::array<Gait, 6> kAllGaits = {Gait::kCrawl,      Gait::kCrawlAlternate,       Gait::kTrot,
                                                  Gait::kPaperCrawl, Gait::kPaperCrawlAlternate, Gait::kWalk};

/// "crawl", "crawl_alt", "trot", "paper_crawl", "paper_crawl_alt" or "walk".
const char* ToString(Gait gait);

/// The gait ToString() names `text`; none for any other text.
std::optional<Gait> ParseGait(std::string_view text);

/// True for the crawls and the walk (one leg at a time, the body balanced over three feet), which
/// the validator holds quasi-static: the body's acceleration bounded, the COM over the support polygon.
bool IsQuasiStatic(Gait gait);

/// True for the gaits whose pace needs the validator's dynamic check in its verdict (the walk and
/// the trot): their weight shifts are too quick for the support polygon alone to say whether the
/// feet can hold them (DynamicsCheckMode::kReport becomes kJudge for them).
bool IsJudgedDynamically(Gait gait);

/// ToString() of a plan's gait; "" when it has none (no controller was chosen).
const char* GaitName(const std::optional<Gait>& gait);

}  // namespace stairplan
