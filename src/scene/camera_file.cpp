#include "scene/camera_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <pugixml.hpp>

#include "common/error.h"
#include "common/file_util.h"

namespace sm::scene {
namespace {

constexpr const char* kRoot = "PVCameraConfiguration";

// One <Property>'s elements by index, checked against its number_of_elements.
class PropertyReader {
 public:
  PropertyReader(const pugi::xml_node& proxy, const std::string& file)
      : proxy_(proxy), file_(file) {}

  pugi::xml_node find(const char* name) const {
    pugi::xml_node found;
    for (pugi::xml_node p : proxy_.children("Property"))
      if (std::strcmp(p.attribute("name").value(), name) == 0) {
        if (found) throw FileError(file_, "property ", name, " is given twice");
        found = p;
      }
    return found;
  }

  std::vector<double> values(const char* name, size_t count) const {
    const pugi::xml_node p = find(name);
    if (!p) throw FileError(file_, "property ", name, " is missing");
    return values(p, name, count);
  }

  std::optional<std::vector<double>> optionalValues(const char* name, size_t count) const {
    const pugi::xml_node p = find(name);
    if (!p) return std::nullopt;
    return values(p, name, count);
  }

 private:
  std::vector<double> values(const pugi::xml_node& p, const char* name, size_t count) const {
    const pugi::xml_attribute declared = p.attribute("number_of_elements");
    if (declared && std::strcmp(declared.value(), std::to_string(count).c_str()) != 0)
      throw FileError(file_, "property ", name, " has number_of_elements=\"", declared.value(),
                      "\", not ", count);
    std::vector<std::optional<double>> v(count);
    for (pugi::xml_node e : p.children("Element")) {
      const std::string index = e.attribute("index").value();
      const std::optional<double> at = number(index);
      if (!at || *at < 0 || *at >= double(count) || *at != std::floor(*at))
        throw FileError(file_, "property ", name, ": element index '", index, "' is not in 0 .. ",
                        count - 1);
      const size_t i = size_t(*at);
      if (v[i]) throw FileError(file_, "property ", name, ": element ", i, " is given twice");
      const pugi::xml_attribute value = e.attribute("value");
      if (!value) throw FileError(file_, "property ", name, ": element ", i, " has no value");
      v[i] = number(value.value());
      if (!v[i])
        throw FileError(file_, "property ", name, ": element ", i, " value '", value.value(),
                        "' is not a finite number");
    }
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) {
      if (!v[i]) throw FileError(file_, "property ", name, ": element ", i, " is missing");
      out.push_back(*v[i]);
    }
    return out;
  }

  // The whole text as a finite number, or nothing.
  static std::optional<double> number(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
      return std::nullopt;
    return v;
  }

  pugi::xml_node proxy_;
  const std::string& file_;
};

glm::dvec3 vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

Camera parseCameraFile(std::string_view text, const std::string& name) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_buffer(text.data(), text.size());
  if (!ok)
    throw FileError(name, "is not well-formed XML (", ok.description(), " at byte ", ok.offset,
                    "): not a ParaView camera file");
  const pugi::xml_node root = doc.document_element();
  if (std::strcmp(root.name(), kRoot) != 0)
    throw FileError(name, "the root element is <", root.name(), ">, not <", kRoot,
                    ">: not a ParaView camera file (.pvcc)");
  pugi::xml_node proxy;
  for (pugi::xml_node p : root.children("Proxy"))
    if (std::strcmp(p.attribute("group").value(), "views") == 0) {
      if (proxy) throw FileError(name, "holds more than one view <Proxy group=\"views\">");
      proxy = p;
    }
  if (!proxy) throw FileError(name, "has no view <Proxy group=\"views\"> in <", kRoot, ">");
  const PropertyReader props(proxy, name);
  Camera c;
  c.eye = vec3(props.values("CameraPosition", 3));
  c.at = vec3(props.values("CameraFocalPoint", 3));
  c.up = vec3(props.values("CameraViewUp", 3));
  c.fovyDeg = props.values("CameraViewAngle", 1)[0];
  const double projection =
      props.optionalValues("CameraParallelProjection", 1).value_or(std::vector<double>{0})[0];
  if (projection != 0 && projection != 1)
    throw FileError(name, "property CameraParallelProjection is ", projection, ", not 0 or 1");
  c.parallel = projection == 1;
  if (c.parallel)
    c.parallelScale = props.values("CameraParallelScale", 1)[0];
  else if (auto scale = props.optionalValues("CameraParallelScale", 1))
    c.parallelScale = (*scale)[0];

  // What cameraFrame would refuse, said here in the file's terms.
  if (c.eye == c.at)
    throw FileError(name, "properties CameraPosition and CameraFocalPoint are the same point");
  if (!(c.fovyDeg > 0 && c.fovyDeg < 180))
    throw FileError(name, "property CameraViewAngle is ", c.fovyDeg, ", not in (0, 180) degrees");
  const glm::dvec3 f = glm::normalize(c.at - c.eye);
  if (!(glm::length(c.up) > 0) || glm::length(glm::cross(f, c.up)) < 1e-12 * glm::length(c.up))
    throw FileError(name, "property CameraViewUp is zero or parallel to the viewing direction");
  if (c.parallel && !(c.parallelScale > 0 && c.parallelScale < 1e30))
    throw FileError(name, "property CameraParallelScale is ", c.parallelScale,
                    ", not a positive length");
  if (!c.parallel && !(c.parallelScale > 0 && c.parallelScale < 1e30)) c.parallelScale = 1.0;
  return c;
}

Camera readCameraFile(const std::string& path) {
  return parseCameraFile(readTextFile(path), path);
}

std::string cameraFileText(const Camera& c) {
  // ParaView's writer (vtkSMCameraConfigurationWriter) gives the proxy the view's id; any id
  // reads back.
  const std::string id = "1";
  auto number = [](double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  auto property = [&](const char* name, const std::vector<double>& v, const char* domain) {
    std::string s = "    <Property name=\"" + std::string(name) + "\" id=\"" + id + "." + name +
                    "\" number_of_elements=\"" + std::to_string(v.size()) + "\">\n";
    for (size_t i = 0; i < v.size(); ++i)
      s += "      <Element index=\"" + std::to_string(i) + "\" value=\"" + number(v[i]) + "\"/>\n";
    if (domain)
      s += "      <Domain name=\"" + std::string(domain) + "\" id=\"" + id + "." + name + "." +
           domain + "\"/>\n";
    return s + "    </Property>\n";
  };
  auto v3 = [](const glm::dvec3& v) { return std::vector<double>{v.x, v.y, v.z}; };
  return std::string("<?xml version=\"1.0\"?>\n") + "<" + kRoot +
         " description=\"ParaView camera configuration\" version=\"1.0\">\n" +
         "  <Proxy group=\"views\" type=\"RenderView\" id=\"" + id + "\" servers=\"21\">\n" +
         property("CameraPosition", v3(c.eye), nullptr) +
         property("CameraFocalPoint", v3(c.at), nullptr) +
         property("CameraViewUp", v3(c.up), nullptr) +
         property("CenterOfRotation", v3(c.at), nullptr) +
         property("RotationFactor", {1.0}, nullptr) +
         property("CameraViewAngle", {c.fovyDeg}, nullptr) +
         property("CameraParallelScale", {c.parallelScale}, nullptr) +
         property("CameraParallelProjection", {c.parallel ? 1.0 : 0.0}, "bool") + "  </Proxy>\n" +
         "</" + kRoot + ">\n";
}

void writeCameraFile(const std::string& path, const Camera& c) {
  const std::string text = cameraFileText(c);
  writeBytesAtomically(
      path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace sm::scene
