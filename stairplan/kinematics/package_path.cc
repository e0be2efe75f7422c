#include "stairplan/kinematics/package_path.h"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace stairplan {
namespace {

namespace fs = std::filesystem;

// rospack's crawl is unbounded; ours stops at a depth and a folder count so that a search path
// pointing at / cannot stall a planner for minutes.
constexpr int kMaxCrawlDepth = 4;
constexpr int kMaxCrawlFolders = 20000;

// The <name> of the package.xml in `folder`, "" when there is none.
std::string PackageXmlName(const fs::path& folder) {
  std::ifstream in(folder / "package.xml");
  if (!in) return "";
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::size_t open = text.find("<name>");
  const std::size_t close = open == std::string::npos ? open : text.find("</name>", open);
  if (close == std::string::npos) return "";
  std::string name = text.substr(open + 6, close - open - 6);
  name.erase(0, name.find_first_not_of(" \t\r\n"));
  name.erase(name.find_last_not_of(" \t\r\n") + 1);
  return name;
}

bool IsDirectory(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool IsFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

bool Ignored(const fs::path& folder) {
  const std::string name = folder.filename().string();
  if (!name.empty() && name[0] == '.') return true;
  for (const char* marker : {"COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE"}) {
    std::error_code ec;
    if (fs::exists(folder / marker, ec)) return true;
  }
  return false;
}

// The folder of package `name` at or below `root`, "" when not found (breadth first, so the
// shallowest match wins, as the folder named NAME directly in a search folder should).
std::string FindPackage(const std::string& name, std::string root) {
  while (root.size() > 1 && root.back() == '/') root.pop_back();  // "dir/" has no file name
  std::deque<std::pair<fs::path, int>> queue = {{fs::path(root), 0}};
  int visited = 0;
  while (!queue.empty() && visited < kMaxCrawlFolders) {
    const auto [folder, depth] = queue.front();
    queue.pop_front();
    ++visited;
    const std::string declared = PackageXmlName(folder);
    if (declared == name || (declared.empty() && folder.filename() == name)) return folder.string();
    if (!declared.empty() || depth >= kMaxCrawlDepth) continue;  // rospack does not descend into packages
    std::error_code ec;
    std::vector<fs::path> children;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      if (IsDirectory(it->path()) && !Ignored(it->path())) children.push_back(it->path());
    }
    std::sort(children.begin(), children.end());  // deterministic whatever the file system's order
    for (const fs::path& child : children) queue.emplace_back(child, depth + 1);
  }
  return "";
}

std::string FolderList(const PackagePath& search) {
  if (search.folders.empty()) return "(none: give --package-path or set ROS_PACKAGE_PATH)";
  std::string list;
  for (const std::string& folder : search.folders) list += (list.empty() ? "" : ", ") + folder;
  return list;
}

ResolvedUri RequireFile(ResolvedUri resolved, const std::string& uri, const std::string& context) {
  if (!IsFile(resolved.path)) {
    throw std::invalid_argument(context + ": mesh '" + uri + "': no such file '" + resolved.path + "'");
  }
  return resolved;
}

}  // namespace

PackagePath PackagePath::FromString(const std::string& colon_separated) {
  PackagePath path;
  std::stringstream in(colon_separated);
  for (std::string folder; std::getline(in, folder, ':');) {
    if (!folder.empty()) path.folders.push_back(folder);
  }
  return path;
}

PackagePath PackagePath::FromEnvironment() {
  const char* value = std::getenv("ROS_PACKAGE_PATH");
  return value ? FromString(value) : PackagePath{};
}

PackagePath PackagePath::Then(const PackagePath& more) const {
  PackagePath joined = *this;
  for (const std::string& folder : more.folders) {
    if (std::find(joined.folders.begin(), joined.folders.end(), folder) == joined.folders.end()) {
      joined.folders.push_back(folder);
    }
  }
  return joined;
}

ResolvedUri ResolveMeshUri(const std::string& uri, const std::string& urdf_folder, const PackagePath& search,
                           const std::string& context) {
  if (uri.empty()) throw std::invalid_argument(context + ": <mesh filename=\"\">: the mesh file name is empty");
  const std::string package_scheme = "package://", file_scheme = "file://";
  if (uri.rfind(package_scheme, 0) == 0) {
    const std::string rest = uri.substr(package_scheme.size());
    const std::size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (name.empty() || inside.empty()) {
      throw std::invalid_argument(context + ": mesh '" + uri + "': a package URI is package://NAME/path/to/file");
    }
    for (const std::string& folder : search.folders) {
      if (!IsDirectory(folder)) continue;
      const std::string package = FindPackage(name, folder);
      if (!package.empty()) return RequireFile({(fs::path(package) / inside).string(), package}, uri, context);
    }
    throw std::invalid_argument(context + ": mesh '" + uri + "': package '" + name +
                                "' not found in the package search path: " + FolderList(search));
  }
  if (uri.rfind(file_scheme, 0) == 0) return RequireFile({uri.substr(file_scheme.size()), ""}, uri, context);
  if (uri.find("://") != std::string::npos) {
    throw std::invalid_argument(context + ": mesh '" + uri + "': unsupported URI scheme (package://, file:// or a path)");
  }
  const fs::path path(uri);
  return RequireFile({path.is_absolute() ? uri : (fs::path(urdf_folder) / path).string(), ""}, uri, context);
}

}  // namespace stairplan
