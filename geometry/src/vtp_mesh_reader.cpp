// VTK XML PolyData (.vtp; VTK's file format description, "XML File Formats": the format 3D
// Slicer, VMTK and ParaView write segmented vessel surfaces in): <VTKFile type="PolyData"> with
// one <Piece NumberOfPoints="V" NumberOfPolys="F">, the points in <Points><DataArray
// NumberOfComponents="3"> and the polygons in <Polys> as two DataArrays, "connectivity" (the
// corners of every polygon, one after another) and "offsets" (where each polygon ends in it).
// DataArrays in format="ascii" (whitespace-separated numbers) or format="binary" (base64 of a
// header, the byte count as UInt32 or UInt64 by the file's header_type, then the values in the
// file's byte_order), of types Float32/Float64 (points) and Int8..UInt64 (indices). Compressed
// data (a "compressor" attribute) and appended data (format="appended") are refused with what to
// do instead; verts, lines and strips are ignored (a surface's triangles are its polys).
// The XML is scanned, not validated: only the elements above are looked for.
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "mesh_parsing.hpp"

namespace filum::geometry::mesh_parsing {

namespace {

/// One start tag: its name, its attributes' raw text, and where its content starts.
struct Tag {
  std::size_t start = 0;  // the '<'
  std::string_view attributes;
  std::size_t content = std::string_view::npos;  // just after '>'
  bool empty = false;                              // "<... />"
};

class VtpScanner {
 public:
  VtpScanner(std::string_view bytes, const std::string& name) : bytes_(bytes), cursor_(bytes, name) {}

  /// The first start tag <name ...> at or after `from` (and before `until`); fails if none.
  Tag tag(const std::string& name, std::size_t from, std::size_t until, const std::string& what) const {
    const std::string open = "<" + name;
    for (std::size_t at = bytes_.find(open, from); at != std::string_view::npos && at < until;
         at = bytes_.find(open, at + 1)) {
      const std::size_t after = at + open.size();
      if (after >= bytes_.size()) break;
      const char c = bytes_[after];
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != '>' && c != '/') continue;  // a longer name
      const std::size_t close = bytes_.find('>', after);
      if (close == std::string_view::npos || close >= until) failAt(at, "a '>' closing <" + name, "the end of the file");
      Tag t;
      t.start = at;
      t.empty = bytes_[close - 1] == '/';
      t.attributes = bytes_.substr(after, close - after - (t.empty ? 1 : 0));
      t.content = close + 1;
      return t;
    }
    failAt(from, what, "none");
  }
  /// Where </name> starts after `from` (fails if missing).
  std::size_t end(const std::string& name, std::size_t from) const {
    const std::size_t at = bytes_.find("</" + name, from);
    if (at == std::string_view::npos) failAt(from, "a closing </" + name + ">", "the end of the file");
    return at;
  }
  /// The value of attribute `key` ("" if absent).
  static std::string_view attribute(std::string_view attributes, std::string_view key) {
    for (std::size_t at = attributes.find(key); at != std::string_view::npos; at = attributes.find(key, at + 1)) {
      if (at > 0 && attributes[at - 1] != ' ' && attributes[at - 1] != '\t' && attributes[at - 1] != '\n' &&
          attributes[at - 1] != '\r')
        continue;
      std::size_t i = at + key.size();
      while (i < attributes.size() && (attributes[i] == ' ' || attributes[i] == '\t')) ++i;
      if (i >= attributes.size() || attributes[i] != '=') continue;
      ++i;
      while (i < attributes.size() && (attributes[i] == ' ' || attributes[i] == '\t')) ++i;
      if (i >= attributes.size() || (attributes[i] != '"' && attributes[i] != '\'')) continue;
      const char quote = attributes[i];
      const std::size_t close = attributes.find(quote, i + 1);
      if (close == std::string_view::npos) return {};
      return attributes.substr(i + 1, close - i - 1);
    }
    return {};
  }
  [[noreturn]] void failAt(std::size_t offset, const std::string& expected, const std::string& found) const {
    // The line of the byte, for the message.
    long line = 1;
    for (std::size_t i = 0; i < offset && i < bytes_.size(); ++i) line += bytes_[i] == '\n';
    Cursor at(std::string_view(), cursor_.name(), true, line);
    at.fail(expected, found);
  }
  std::string_view bytes() const { return bytes_; }
  const Cursor& cursor() const { return cursor_; }

 private:
  std::string_view bytes_;
  Cursor cursor_;
};

/// The file-wide settings of binary data.
struct Encoding {
  bool big_endian = false;
  bool header64 = false;
};

/// The values of one DataArray as doubles (indices too: exact below 2^53, and checked as
/// integers by the caller), at most `limit` of them.
std::vector<double> dataArray(const VtpScanner& scan, const Tag& tag, const Encoding& encoding, long long limit,
                              const std::string& what) {
  const std::string_view format = VtpScanner::attribute(tag.attributes, "format");
  const std::string_view type = VtpScanner::attribute(tag.attributes, "type");
  const std::size_t stop = tag.empty ? tag.content : scan.end("DataArray", tag.content);
  const std::string_view text = scan.bytes().substr(tag.content, stop - tag.content);
  std::vector<double> out;
  if (format == "appended")
    scan.failAt(tag.content, what + " inline (format \"ascii\" or \"binary\"; ParaView: save with Data Mode Ascii or "
                                    "Binary and no compression)",
                "format=\"appended\"");
  if (format == "ascii") {
    Cursor words(text, scan.cursor().name());
    std::string_view word;
    while (words.nextWord(word)) {
      if (static_cast<long long>(out.size()) >= limit)
        scan.failAt(tag.content, what + " of at most " + std::to_string(limit) + " values (as the Piece's counts say)",
                    "more");
      double value = 0.0;
      if (!parseNumber(word, value)) scan.failAt(tag.content, what + ": numbers", quoted(word));
      out.push_back(value);
    }
    return out;
  }
  if (format != "binary")
    scan.failAt(tag.content, what + " in format \"ascii\" or \"binary\"", quoted(format.empty() ? "none" : format));
  // Base64 (RFC 4648) of the whole array: header, then the values.
  std::vector<unsigned char> raw;
  raw.reserve(text.size() / 4 * 3);
  std::array<int, 4> quad{};
  int filled = 0;
  for (const char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+') v = 62;
    else if (c == '/') v = 63;
    else if (c == '=' || c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
    else scan.failAt(tag.content, what + ": base64 data", quoted(std::string_view(&c, 1)));
    quad[filled++] = v;
    if (filled == 4) {
      raw.push_back(static_cast<unsigned char>((quad[0] << 2) | (quad[1] >> 4)));
      raw.push_back(static_cast<unsigned char>(((quad[1] & 15) << 4) | (quad[2] >> 2)));
      raw.push_back(static_cast<unsigned char>(((quad[2] & 3) << 6) | quad[3]));
      filled = 0;
    }
  }
  if (filled >= 2) raw.push_back(static_cast<unsigned char>((quad[0] << 2) | (quad[1] >> 4)));
  if (filled == 3) raw.push_back(static_cast<unsigned char>(((quad[1] & 15) << 4) | (quad[2] >> 2)));
  const auto unsignedAt = [&](std::size_t at, int size) {
    unsigned long long value = 0;
    for (int b = 0; b < size; ++b) {
      const unsigned long long byte = raw[at + (encoding.big_endian ? b : size - 1 - b)];
      value = (value << 8) | byte;
    }
    return value;
  };
  const int header = encoding.header64 ? 8 : 4;
  if (raw.size() < static_cast<std::size_t>(header))
    scan.failAt(tag.content, what + ": a " + std::to_string(header) + "-byte header of the data's size", "less");
  const unsigned long long count_bytes = unsignedAt(0, header);
  if (count_bytes > raw.size() - header)
    scan.failAt(tag.content, what + ": " + std::to_string(count_bytes) + " bytes of data as its header says",
                std::to_string(raw.size() - header));
  struct Type {
    const char* name;
    int size;
    bool floating, is_signed;
  };
  static constexpr Type kTypes[] = {{"Float32", 4, true, true}, {"Float64", 8, true, true}, {"Int8", 1, false, true},
                                    {"UInt8", 1, false, false}, {"Int16", 2, false, true},  {"UInt16", 2, false, false},
                                    {"Int32", 4, false, true},  {"UInt32", 4, false, false}, {"Int64", 8, false, true},
                                    {"UInt64", 8, false, false}};
  const Type* t = nullptr;
  for (const Type& k : kTypes)
    if (type == k.name) t = &k;
  if (!t) scan.failAt(tag.content, what + " of a numeric type (Float32, Float64, Int8 ... UInt64)", quoted(type));
  const unsigned long long n = count_bytes / static_cast<unsigned long long>(t->size);
  if (static_cast<long long>(n) > limit || n > static_cast<unsigned long long>(limit))
    scan.failAt(tag.content, what + " of at most " + std::to_string(limit) + " values", std::to_string(n));
  out.reserve(static_cast<std::size_t>(n));
  for (unsigned long long i = 0; i < n; ++i) {
    const std::size_t at = header + static_cast<std::size_t>(i) * t->size;
    const unsigned long long bits = unsignedAt(at, t->size);
    double value;
    if (t->floating && t->size == 4) {
      float f;
      const auto u = static_cast<std::uint32_t>(bits);
      std::memcpy(&f, &u, 4);
      value = f;
    } else if (t->floating) {
      std::memcpy(&value, &bits, 8);
    } else if (t->is_signed) {
      const int shift = 64 - 8 * t->size;  // sign-extend
      value = static_cast<double>(static_cast<long long>(bits << shift) >> shift);
    } else {
      value = static_cast<double>(bits);
    }
    out.push_back(value);
  }
  return out;
}

/// The DataArray named `name` inside [from, until), or the first one when name is empty.
Tag namedArray(const VtpScanner& scan, std::size_t from, std::size_t until, const std::string& name,
               const std::string& what) {
  for (std::size_t at = from;;) {
    const Tag t = scan.tag("DataArray", at, until, what);
    if (name.empty() || VtpScanner::attribute(t.attributes, "Name") == name) return t;
    at = t.content;
  }
}

long long count(const VtpScanner& scan, const Tag& piece, std::string_view key) {
  const std::string_view text = VtpScanner::attribute(piece.attributes, key);
  long long value = 0;
  if (text.empty()) return 0;
  if (!parseInteger(text, value) || value < 0)
    scan.failAt(piece.content, "a count " + std::string(key) + "=\"n\" (n >= 0) on the Piece", quoted(text));
  return value;
}

}  // namespace

PolygonSoup readVtp(std::string_view bytes, const std::string& name) {
  const VtpScanner scan(bytes, name);
  SoupBuilder soup(scan.cursor());
  const std::size_t all = bytes.size();
  const Tag file = scan.tag("VTKFile", 0, all, "a VTK XML file (<VTKFile type=\"PolyData\" ...>)");
  if (VtpScanner::attribute(file.attributes, "type") != "PolyData")
    scan.failAt(file.start, "a PolyData file (<VTKFile type=\"PolyData\">)",
                quoted(VtpScanner::attribute(file.attributes, "type")));
  if (!VtpScanner::attribute(file.attributes, "compressor").empty())
    scan.failAt(file.start, "uncompressed data (VTK writer: SetCompressorTypeToNone; ParaView: Compressor None)",
                "compressor=\"" + std::string(VtpScanner::attribute(file.attributes, "compressor")) + "\"");
  Encoding encoding;
  encoding.big_endian = VtpScanner::attribute(file.attributes, "byte_order") == "BigEndian";
  const std::string_view header_type = VtpScanner::attribute(file.attributes, "header_type");
  if (!header_type.empty() && header_type != "UInt32" && header_type != "UInt64")
    scan.failAt(file.start, "header_type \"UInt32\" or \"UInt64\"", quoted(header_type));
  encoding.header64 = header_type == "UInt64";

  const Tag piece = scan.tag("Piece", file.content, all, "a <Piece NumberOfPoints=... NumberOfPolys=...>");
  const std::size_t piece_end = scan.end("Piece", piece.content);
  if (bytes.find("<Piece", piece_end) != std::string_view::npos)
    scan.failAt(piece_end, "one Piece (a surface merged into one: VTK's vtkAppendPolyData)", "more than one");
  const long long vertex_count = count(scan, piece, "NumberOfPoints");
  const long long polygon_count = count(scan, piece, "NumberOfPolys");
  if (polygon_count == 0) scan.failAt(piece.content, "polygons (NumberOfPolys > 0): a surface's triangles", "none");
  if (polygon_count > kMaxMeshTriangles)
    scan.failAt(piece.content, "at most " + std::to_string(kMaxMeshTriangles) + " polygons",
                std::to_string(polygon_count));
  soup.expectVertices(vertex_count);

  // Points: 3 V coordinates.
  const Tag points = scan.tag("Points", piece.content, piece_end, "the <Points> of the Piece");
  const std::size_t points_end = scan.end("Points", points.content);
  const Tag coordinates = namedArray(scan, points.content, points_end, "", "the points' <DataArray>");
  const std::string_view components = VtpScanner::attribute(coordinates.attributes, "NumberOfComponents");
  if (components != "3") scan.failAt(coordinates.content, "points of NumberOfComponents=\"3\"", quoted(components));
  const std::vector<double> xyz = dataArray(scan, coordinates, encoding, 3 * vertex_count, "the points");
  if (static_cast<long long>(xyz.size()) != 3 * vertex_count)
    scan.failAt(coordinates.content, std::to_string(3 * vertex_count) + " coordinates (NumberOfPoints × 3)",
                std::to_string(xyz.size()));
  for (long long i = 0; i < vertex_count; ++i) soup.addVertex(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  // Polys: offsets (F ends) into connectivity.
  const Tag polys = scan.tag("Polys", piece.content, piece_end, "the <Polys> of the Piece");
  const std::size_t polys_end = scan.end("Polys", polys.content);
  const std::vector<double> offsets =
      dataArray(scan, namedArray(scan, polys.content, polys_end, "offsets", "the polys' \"offsets\" <DataArray>"),
                encoding, polygon_count, "the polys' offsets");
  if (static_cast<long long>(offsets.size()) != polygon_count)
    scan.failAt(polys.content, std::to_string(polygon_count) + " offsets (NumberOfPolys)", std::to_string(offsets.size()));
  // The connectivity's size is the last offset: at least 3 corners a polygon, and at most the
  // corners of the kMaxMeshTriangles triangles they may fan into (a polygon of n corners gives
  // n − 2 triangles: corners <= triangles + 2 F).
  const double corners = offsets.back();
  if (!(corners >= 3.0 * polygon_count) || corners > static_cast<double>(kMaxMeshTriangles + 2 * polygon_count))
    scan.failAt(polys.content, "a last offset of at least 3 × NumberOfPolys and at most the corners of " +
                                   std::to_string(kMaxMeshTriangles) + " triangles",
                std::to_string(corners));
  const std::vector<double> connectivity = dataArray(
      scan, namedArray(scan, polys.content, polys_end, "connectivity", "the polys' \"connectivity\" <DataArray>"),
      encoding, static_cast<long long>(corners), "the polys' connectivity");
  if (static_cast<double>(connectivity.size()) != corners)
    scan.failAt(polys.content, "a connectivity of " + std::to_string(static_cast<long long>(corners)) +
                                   " indices (the last offset)",
                std::to_string(connectivity.size()));
  std::vector<long long> polygon;
  long long begin = 0;
  for (long long f = 0; f < polygon_count; ++f) {
    const double end = offsets[f];
    if (!(end >= static_cast<double>(begin) + 3.0) || end > corners)
      scan.failAt(polys.content, "offsets that grow by at least 3 (a polygon of 3 or more corners) up to the last",
                  "offset " + std::to_string(f) + " = " + std::to_string(end));
    polygon.clear();
    for (auto i = begin; i < static_cast<long long>(end); ++i) {
      const double index = connectivity[static_cast<std::size_t>(i)];
      if (!(index >= 0.0 && index < static_cast<double>(kMaxMeshVertices)) || index != std::floor(index))
        scan.failAt(polys.content, "indices of points in the connectivity (integers in [0, NumberOfPoints))",
                    std::to_string(index));
      polygon.push_back(static_cast<long long>(index));
    }
    soup.addPolygon(polygon);
    begin = static_cast<long long>(end);
  }
  return soup.finish();
}

}  // namespace filum::geometry::mesh_parsing
