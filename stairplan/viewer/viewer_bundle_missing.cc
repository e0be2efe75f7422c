// The build found no three.js (stairplan/viewer/node_modules): `stairplan view` says so.
#include "stairplan/viewer/viewer_bundle.h"

namespace stairplan {

const std::string& ViewerBundleJs() {
  static const std::string none;
  return none;
}

}  // namespace stairplan
