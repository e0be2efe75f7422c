// `stairplan gait-design`: the 2012 paper's stair-climbing gait design (seed 003) for given stairs
// and robot sizes: l_min, contact offsets, swing separations, the interference conditions with the
// binding one, the swing sequence, quasi-static stability and the tread-depth error tolerance.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "stairplan/geometry/field_error.h"
#include "cli/cli_common.h"
#include "stairplan/planning/gait/crawl_stability.h"
#include "stairplan/planning/gait/feasibility_figure.h"
#include "stairplan/planning/gait/gait_design.h"
#include "stairplan/planning/gait/tread_error.h"
#include "stairplan/planning/json_version.h"

namespace stairplan::cli {
namespace {

// NaN and infinities become null in JSON.
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json StabilityJson(const CrawlStability& s) {
  nlohmann::json by_leg = nlohmann::json::object();
  const char* names[4] = {"RH", "LH", "RF", "LF"};  // CrawlStability's order
  for (std::size_t i = 0; i < 4; ++i) by_leg[names[i]] = s.fraction_outside_by_leg[i];
  nlohmann::json sequence = nlohmann::json::array();
  for (const char* leg : s.swing_sequence) sequence.push_back(leg);
  return {{"swing_sequence", sequence}, {"fraction_outside", s.fraction_outside},
          {"fraction_of_swing_time", s.fraction_of_swing_time}, {"fraction_outside_by_leg", by_leg},
          {"min_margin", Number(s.min_margin)}};
}

// An empty range is said to be empty, not printed as an interval.
std::string ToleranceText(const TreadErrorTolerance& t) {
  std::ostringstream text;
  text << std::setprecision(4);
  if (!std::isfinite(t.lower) || !std::isfinite(t.upper)) {
    text << "none (undefined without D_s > 0)";
  } else if (t.empty()) {
    text << "none (eq. (17) needs dW > " << t.lower << " m and dW < " << t.upper << " m)";
  } else {
    text << t.lower << " < dW < " << t.upper << " m";
  }
  return text.str();
}

int RunGaitDesign(const std::vector<std::string>& args) {
  CLI::App app("The 2012 paper's stair-climbing gait design (lengths in m)", "gait-design");
  GaitDesignInput in;
  std::optional<double> hip_clearance;
  std::vector<double> tread_errors;
  bool json = false;
  std::string figure;
  app.add_option("--rise", in.rise, "Stair rise H [m]")->required();
  app.add_option("--run", in.run, "Tread depth W [m]")->required();
  app.add_option("--lmax", in.max_leg_length, "Maximum leg length l_max, hip to foot [m]")->required();
  app.add_option("--body-length", in.body_length, "Body length BL, front to hind hip [m]")->required();
  app.add_option("--body-width", in.body_width, "Body width BW, left to right foot [m], default 0.36");
  app.add_option("--buffer", in.buffer, "Buffer fraction p of D_s between right and left swings, default 0.42");
  app.add_option("--hip-clearance", hip_clearance, "Hip clearance d above the edge line [m], default rise / 2");
  app.add_option("--tread-errors", tread_errors,
                 "Per-step tread depth errors dW_i [m], comma separated: checks the cumulative error (eq. (19))")
      ->delimiter(',');
  app.add_flag("--json", json, "Print one JSON object instead of the summary");
  app.add_option("--figure", figure,
                 "Write the paper's Figure 4(b), the feasible W/BL and H/BL at this l_max/BL and p, as SVG to this file");
  if (const int code = Parse(app, args); code >= 0) return code;
  return Guarded("gait-design", [&] {
    in.hip_clearance = hip_clearance;
    GaitDesign g;
    try {
      g = DesignGait(in);
    } catch (const FieldError& e) {
      static const std::map<std::string, std::string> kFlags = {
          {"rise", "--rise"}, {"run", "--run"}, {"max_leg_length", "--lmax"}, {"body_length", "--body-length"},
          {"body_width", "--body-width"}, {"buffer", "--buffer"}, {"hip_clearance", "--hip-clearance"}};
      const auto it = kFlags.find(e.field());
      throw BadInput((it == kFlags.end() ? e.field() : it->second) + ": " + e.problem());
    }
    const TreadErrorTolerance tolerance = TreadDepthTolerance(g, in.run, in.rise);
    nlohmann::json conditions = nlohmann::json::array();
    for (const GaitCondition& c : g.conditions) {
      conditions.push_back({{"name", c.name}, {"text", c.text}, {"holds", c.holds}, {"slack", Number(c.slack)}});
    }
    nlohmann::json out = {
        {"rise", in.rise}, {"run", in.run}, {"l_max", in.max_leg_length}, {"body_length", in.body_length},
        {"body_width", in.body_width}, {"buffer", in.buffer}, {"hip_clearance", g.d},
        {"CL", g.cl}, {"phi", g.phi}, {"l_min", g.l_min}, {"a_min", Number(g.a_min)}, {"a_max", Number(g.a_max)},
        {"D_s", Number(g.d_s)}, {"D_i", Number(g.d_i)}, {"D_o", Number(g.d_o)}, {"D_o_share", Number(g.d_o / g.cl)}, {"rem", g.rem},
        {"conditions", conditions}, {"feasible", g.feasible}, {"binding", g.binding},
        {"error_tolerance", {{"dW_min", Number(tolerance.lower)}, {"dW_max", Number(tolerance.upper)}, {"empty", tolerance.empty()}}}};
    StampVersion(out);
    out["cumulative_error"] = nullptr;
    std::optional<CumulativeTreadError> cumulative;
    if (!tread_errors.empty()) {
      try {
        cumulative = CheckCumulativeTreadError(tread_errors, tolerance);
      } catch (const std::invalid_argument& e) {
        throw BadInput(std::string("--tread-errors: ") + e.what());
      }
      out["cumulative_error"] = {{"dW_t", cumulative->cumulative},
                                 {"first_violation", cumulative->first_violation},
                                 {"within", cumulative->within()}};
    }
    out["swing_sequence"] = nullptr;
    out["stability"] = nullptr;
    if (g.d_s > 0.0) {
      const CrawlStability case1 = EvaluateCrawlStability(in, g, CrawlCase::kRightFirst);
      const CrawlStability case2 = EvaluateCrawlStability(in, g, CrawlCase::kFrontSwitched);
      out["swing_sequence"] = StabilityJson(case1)["swing_sequence"];
      out["stability"] = {{"case1", StabilityJson(case1)}, {"case2", StabilityJson(case2)},
                          {"hind_swing_share", HindSwingShare(g)}};
    }
    if (!figure.empty()) {
      std::vector<MarkedStair> stairs = PaperStairs();
      const bool listed = std::any_of(stairs.begin(), stairs.end(), [&](const MarkedStair& s) {
        return std::abs(s.run - in.run) < 1e-9 && std::abs(s.rise - in.rise) < 1e-9;
      });
      if (!listed) stairs.push_back({in.run, in.rise, "this stair"});
      WriteFileAtomically(figure, FeasibilityFigureSvg(in.max_leg_length, in.body_length, in.buffer, stairs));
    }
    if (json) {
      std::cout << out.dump(2) << "\n";
    } else {
      std::cout << std::setprecision(4) << "stairplan gait-design: W " << in.run << " m, H " << in.rise << " m, l_max "
                << in.max_leg_length << " m, BL " << in.body_length << " m, p " << in.buffer << "\n"
                << "  l_min " << g.l_min << " m, CL " << g.cl << " m, d " << g.d << " m\n"
                << "  a_min " << g.a_min << " m, a_max " << g.a_max << " m\n"
                << "  D_s " << g.d_s << " m, D_i " << g.d_i << " m, D_o " << g.d_o << " m, rem(BL, CL) " << g.rem << " m\n";
      for (const GaitCondition& c : g.conditions) {
        std::cout << "  " << std::setw(4) << c.name << " " << (c.holds ? "holds " : "FAILS ") << c.text << " (slack "
                  << c.slack << " m)\n";
      }
      std::cout << "  verdict: " << (g.feasible ? "feasible" : "infeasible") << ", binding " << g.binding << "\n"
                << "  tread error tolerance: " << ToleranceText(tolerance) << "\n";
      if (cumulative) {
        std::cout << "  cumulative tread error over " << tread_errors.size() << " steps: "
                  << (cumulative->within() ? "within the tolerance"
                                           : "leaves the tolerance at step " + std::to_string(cumulative->first_violation + 1))
                  << "\n";
      }
      if (!out["stability"].is_null()) {
        std::cout << "  COM outside the support triangle: case 1 " << out["stability"]["case1"]["fraction_outside"].get<double>() * 100
                  << " %, case 2 " << out["stability"]["case2"]["fraction_outside"].get<double>() * 100
                  << " % of a cycle (a hind leg is in the air " << HindSwingShare(g) * 100 << " %)\n";
      }
    }
    return g.feasible ? kExitOk : kExitInfeasible;
  });
}

const CommandRegistrar kGaitDesignRegistrar({"gait-design", "the 2012 paper's stair gait design (l_min, D_s, D_o, conditions)", RunGaitDesign});

}  // namespace
}  // namespace stairplan::cli
