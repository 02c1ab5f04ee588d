// A small reader of the VTK XML files filum writes (ASCII PolyData .vtp and .pvd collections),
// independent of the writers, for tests that read exported files back: it parses the XML
// elements and attributes and the whitespace-separated numbers of each DataArray.
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace filum::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // character data directly inside the element
  std::vector<XmlElement> children;

  /// First descendant (depth first) with this name and, if given, attribute Name=value.
  const XmlElement* find(const std::string& element, const std::string& array_name = "") const {
    for (const XmlElement& c : children) {
      if (c.name == element && (array_name.empty() || (c.attributes.count("Name") && c.attributes.at("Name") == array_name)))
        return &c;
      if (const XmlElement* d = c.find(element, array_name)) return d;
    }
    return nullptr;
  }
  std::vector<double> numbers() const {
    std::vector<double> out;
    std::istringstream in(text);
    double x;
    while (in >> x) out.push_back(x);
    return out;
  }
};

namespace detail {

inline void skipSpace(const std::string& s, std::size_t& i) {
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
}

inline XmlElement parseElement(const std::string& s, std::size_t& i) {
  // At '<name attr="v" ...>' or '<name .../>'.
  XmlElement e;
  ++i;
  const std::size_t name_end = s.find_first_of(" \t\r\n/>", i);
  e.name = s.substr(i, name_end - i);
  i = name_end;
  while (true) {
    skipSpace(s, i);
    if (s.compare(i, 2, "/>") == 0) {
      i += 2;
      return e;
    }
    if (s[i] == '>') {
      ++i;
      break;
    }
    const std::size_t eq = s.find('=', i);
    const std::string key = s.substr(i, eq - i);
    const std::size_t open = s.find('"', eq), close = s.find('"', open + 1);
    e.attributes[key] = s.substr(open + 1, close - open - 1);
    i = close + 1;
  }
  // Content until the closing tag.
  while (i < s.size()) {
    const std::size_t lt = s.find('<', i);
    if (lt == std::string::npos) throw std::runtime_error("unterminated element " + e.name);
    e.text += s.substr(i, lt - i);
    i = lt;
    if (s.compare(i, 2, "</") == 0) {
      const std::size_t gt = s.find('>', i);
      if (s.substr(i + 2, gt - i - 2) != e.name) throw std::runtime_error("mismatched closing tag for " + e.name);
      i = gt + 1;
      return e;
    }
    e.children.push_back(parseElement(s, i));
  }
  throw std::runtime_error("unterminated element " + e.name);
}

}  // namespace detail

/// The root element of an XML file (the declaration "<?xml ...?>" is skipped).
inline XmlElement readXml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string s = buffer.str();
  std::size_t i = s.find('<');
  if (s.compare(i, 2, "<?") == 0) i = s.find('<', s.find("?>", i));
  return detail::parseElement(s, i);
}

/// Points, normals and triangles of a .vtp written by writeMeshVtp.
struct VtpMesh {
  std::vector<double> points, normals;
  std::vector<int> connectivity, offsets;
  int number_of_points = 0, number_of_polys = 0;
};

inline VtpMesh readVtpMesh(const std::string& path) {
  const XmlElement root = readXml(path);
  if (root.name != "VTKFile" || root.attributes.at("type") != "PolyData") throw std::runtime_error(path + ": not PolyData");
  const XmlElement* piece = root.find("Piece");
  if (!piece) throw std::runtime_error(path + ": no Piece");
  VtpMesh m;
  m.number_of_points = std::stoi(piece->attributes.at("NumberOfPoints"));
  m.number_of_polys = std::stoi(piece->attributes.at("NumberOfPolys"));
  const XmlElement* points = piece->find("Points");
  m.points = points->find("DataArray")->numbers();
  m.normals = piece->find("PointData")->find("DataArray", "Normals")->numbers();
  for (double x : piece->find("Polys")->find("DataArray", "connectivity")->numbers()) m.connectivity.push_back(static_cast<int>(x));
  for (double x : piece->find("Polys")->find("DataArray", "offsets")->numbers()) m.offsets.push_back(static_cast<int>(x));
  return m;
}

struct PvdEntry {
  double time;
  int part;
  std::string file;
};

inline std::vector<PvdEntry> readPvd(const std::string& path) {
  const XmlElement root = readXml(path);
  const XmlElement* collection = root.find("Collection");
  if (root.name != "VTKFile" || !collection) throw std::runtime_error(path + ": not a collection");
  std::vector<PvdEntry> out;
  for (const XmlElement& d : collection->children)
    out.push_back({std::stod(d.attributes.at("timestep")), std::stoi(d.attributes.at("part")), d.attributes.at("file")});
  return out;
}

}  // namespace filum::test
