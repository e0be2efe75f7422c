// The viewer's one self-contained HTML page: the scene as JSON and the bundled script (three.js
// included) inline, so it opens from disk with no server and no network.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace stairplan {

/// The page showing `scene` (BuildViewerScene) with the page script `script` (ViewerBundleJs()).
/// Open it with `#t=SECONDS` to start paused at that time.
std::string ViewerPageHtml(const nlohmann::json& scene, const std::string& script);

}  // namespace stairplan
