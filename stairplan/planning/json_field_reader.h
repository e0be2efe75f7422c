// Field access into a parsed JSON file that names the file and the path of what is missing or
// wrong: "<source>: field '<path>': <problem>" (std::invalid_argument). The plan.json reader and
// the viewer's reader of simulation output share it.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace stairplan {

/// Reads typed fields of a JSON document; every error is std::invalid_argument naming the source
/// and the field's path.
class JsonFieldReader {
 public:
  using json = nlohmann::json;  ///< nlohmann's JSON value

  /// `source` names the document (e.g. its file) in errors.
  explicit JsonFieldReader(std::string source) : source_(std::move(source)) {}

  /// Throws "<source>: field '<path>': <problem>".
  [[noreturn]] void Fail(const std::string& path, const std::string& problem) const {
    throw std::invalid_argument(source_ + ": field '" + path + "': " + problem);
  }
  /// `node[key]`; fails when `node` is not an object holding `key`. `path` is the key's prefix in errors.
  const json& At(const json& node, const std::string& key, const std::string& path) const {
    if (!node.is_object() || !node.contains(key)) Fail(path + key, "missing");
    return node.at(key);
  }
  /// `node[key]` as a finite number.
  double Number(const json& node, const std::string& key, const std::string& path) const {
    const json& v = At(node, key, path);
    if (!v.is_number()) Fail(path + key, "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) Fail(path + key, "must be finite");
    return d;
  }
  /// `node[key]` as a string.
  std::string Text(const json& node, const std::string& key, const std::string& path) const {
    const json& v = At(node, key, path);
    if (!v.is_string()) Fail(path + key, "must be a string");
    return v.get<std::string>();
  }
  /// `node[key]` as an array.
  const json& Array(const json& node, const std::string& key, const std::string& path) const {
    const json& v = At(node, key, path);
    if (!v.is_array()) Fail(path + key, "must be an array");
    return v;
  }
  /// The point of `node`'s x, y and z fields.
  Eigen::Vector3d Point(const json& node, const std::string& path) const {
    return {Number(node, "x", path), Number(node, "y", path), Number(node, "z", path)};
  }
  /// A [x, y, z] array of finite numbers.
  Eigen::Vector3d Triple(const json& node, const std::string& key, const std::string& path) const {
    const json& v = Array(node, key, path);
    if (v.size() != 3) Fail(path + key, "must hold 3 numbers");
    Eigen::Vector3d out;
    for (std::size_t i = 0; i < 3; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) Fail(path + key, "must hold 3 finite numbers");
      out(static_cast<Eigen::Index>(i)) = v[i].get<double>();
    }
    return out;
  }

 private:
  std::string source_;
};

}  // namespace stairplan
