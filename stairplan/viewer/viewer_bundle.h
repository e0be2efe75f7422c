// The viewer page's script: ours and three.js (from npm) bundled by esbuild at build time.
#pragma once

#include <string>

namespace stairplan {

/// The bundled script; empty when the build had no three.js (stairplan/viewer/node_modules missing:
/// scripts/setup.sh runs `npm ci` there).
const std::string& ViewerBundleJs();

}  // namespace stairplan
