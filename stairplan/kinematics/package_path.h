// Resolving the resource URIs of a URDF's <mesh filename="..."> the way ROS does: `package://NAME/rest`
// through a list of package search folders (ROS_PACKAGE_PATH, or --package-path on the CLI),
// `file:///abs/path`, and plain paths, relative ones taken from the URDF's own folder.
#pragma once

#include <string>
#include <vector>

namespace stairplan {

/// Folders searched for `package://` URIs, in order.
struct PackagePath {
  std::vector<std::string> folders;  ///< search folders, in order

  /// Splits "DIR[:DIR...]" (empty entries are dropped).
  static PackagePath FromString(const std::string& colon_separated);
  /// The folders of the ROS_PACKAGE_PATH environment variable (none when unset).
  static PackagePath FromEnvironment();
  /// These folders followed by `more`'s (duplicates kept once, first place wins).
  PackagePath Then(const PackagePath& more) const;
};

/// Where one URI was resolved to, or why not.
struct ResolvedUri {
  std::string path;     ///< the file, when found
  std::string package;  ///< the package folder a package:// URI resolved to ("" otherwise)
};

/// Resolves `uri` as ROS does. A package is found as a folder named NAME, or holding a package.xml
/// whose `<name>` is NAME, in or below a search folder (a bounded crawl that does not descend into
/// packages, hidden folders or folders marked COLCON_IGNORE/CATKIN_IGNORE/AMENT_IGNORE). Throws
/// std::invalid_argument starting with `context` (e.g. "robot.urdf: <link name=\"x\">") that names
/// the URI and, for an unknown package, every folder searched; for a missing file, its path.
ResolvedUri ResolveMeshUri(const std::string& uri, const std::string& urdf_folder, const PackagePath& search,
                           const std::string& context);

}  // namespace stairplan
