// The build found no three.js (planning/viewer/node_modules): `stairplan view` says so.
#include "planning/viewer/viewer_bundle.h"

namespace stairplan {

const std::string& ViewerBundleJs() {
  static const std::string none;
  return none;
}

}  // namespace stairplan
