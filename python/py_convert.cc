// Conversions between Python objects and the library's JSON, paths and numpy structured arrays.
#include <cmath>
#include <filesystem>

#include "bindings.h"

namespace stairplan::python {

py::object ToPython(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, value] : json.items()) out[py::str(key)] = ToPython(value);
      return std::move(out);
    }
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& value : json) out.append(ToPython(value));
      return std::move(out);
    }
    case nlohmann::json::value_t::string:
      return py::str(json.get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(json.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(json.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double value = json.get<double>();
      return std::isfinite(value) ? py::object(py::float_(value)) : py::none();
    }
    default:
      return py::none();
  }
}

nlohmann::json FromPython(const py::handle& object, const std::string& where) {
  if (object.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(object)) return object.cast<bool>();
  if (py::isinstance<py::int_>(object)) return object.cast<std::int64_t>();
  if (py::isinstance<py::float_>(object)) return object.cast<double>();
  if (py::isinstance<py::str>(object)) return object.cast<std::string>();
  if (py::isinstance<py::dict>(object)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : object.cast<py::dict>()) {
      const std::string name = py::str(key);
      out[name] = FromPython(value, where.empty() ? name : where + "." + name);
    }
    return out;
  }
  if (py::hasattr(object, "__fspath__")) return PathArg(object, where);
  if (py::hasattr(object, "tolist")) return FromPython(object.attr("tolist")(), where);  // numpy
  if (py::isinstance<py::list>(object) || py::isinstance<py::tuple>(object)) {
    nlohmann::json out = nlohmann::json::array();
    int i = 0;
    for (const auto& value : object) out.push_back(FromPython(value, where + "[" + std::to_string(i++) + "]"));
    return out;
  }
  throw py::type_error(where + ": unsupported type " + std::string(py::str(object.get_type().attr("__name__"))));
}

std::string PathArg(const py::handle& object, const std::string& what) {
  if (py::isinstance<py::str>(object)) return object.cast<std::string>();
  if (py::hasattr(object, "__fspath__")) return py::str(object.attr("__fspath__")());
  throw py::type_error(what + ": expected a path (str or os.PathLike)");
}

void RequireFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw FileNotFound(path);
}

py::object StructuredArray(const std::vector<std::pair<std::string, py::object>>& columns) {
  const py::module_ numpy = py::module_::import("numpy");
  py::list fields;
  py::ssize_t rows = 0;
  for (const auto& [name, column] : columns) {
    const py::object array = numpy.attr("asarray")(column);
    fields.append(py::make_tuple(name, array.attr("dtype")));
    rows = py::len(array);
  }
  py::object out = numpy.attr("empty")(rows, py::arg("dtype") = numpy.attr("dtype")(fields));
  for (const auto& [name, column] : columns) out[py::str(name)] = column;
  return out;
}

}  // namespace stairplan::python
