// Stanford PLY (mesh_file.hpp; scanners, MeshLab, Blender): a text header of elements and their
// properties, then the data in ascii or binary (little- or big-endian). The "vertex" element's
// x, y, z and the "face" element's vertex index list are kept; everything else is read past.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "mesh_parsing.hpp"

namespace filum::geometry::mesh_parsing {

namespace {

enum class Encoding { kAscii, kLittleEndian, kBigEndian };
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

// The type of a PLY type name (both the old and the sized spellings); false if unknown.
bool typeOf(std::string_view name, Type& type) {
  struct Named {
    std::string_view name;
    Type type;
  };
  static constexpr Named kTypes[] = {
      {"char", Type::kInt8},     {"int8", Type::kInt8},     {"uchar", Type::kUint8},   {"uint8", Type::kUint8},
      {"short", Type::kInt16},   {"int16", Type::kInt16},   {"ushort", Type::kUint16}, {"uint16", Type::kUint16},
      {"int", Type::kInt32},     {"int32", Type::kInt32},   {"uint", Type::kUint32},   {"uint32", Type::kUint32},
      {"float", Type::kFloat32}, {"float32", Type::kFloat32}, {"double", Type::kFloat64}, {"float64", Type::kFloat64}};
  for (const Named& t : kTypes)
    if (t.name == name) {
      type = t.type;
      return true;
    }
  return false;
}

int sizeOf(Type type) {
  switch (type) {
    case Type::kInt8:
    case Type::kUint8: return 1;
    case Type::kInt16:
    case Type::kUint16: return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 8;
}

struct Property {
  std::string name;
  Type type = Type::kFloat64;  // the scalar's type, or a list's item type
  bool list = false;
  Type count_type = Type::kUint8;  // lists only
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

/// Header entries (elements and properties), at most: real files have a few dozen.
constexpr int kMaxHeaderEntries = 1000;

template <class T>
double decode(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);
  return static_cast<double>(value);
}

// Values of the data section, one after another, as doubles (exact for every PLY integer type).
class Values {
 public:
  Values(Cursor& cursor, Encoding encoding) : cursor_(cursor), encoding_(encoding) {}

  double next(Type type) {
    if (encoding_ == Encoding::kAscii) return cursor_.number(kAsciiValue);
    const int size = sizeOf(type);
    const std::string_view raw = cursor_.take(static_cast<std::size_t>(size), "a binary value");
    unsigned char bytes[8];
    std::memcpy(bytes, raw.data(), static_cast<std::size_t>(size));
    if ((encoding_ == Encoding::kLittleEndian) != (std::endian::native == std::endian::little))
      for (int i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    switch (type) {
      case Type::kInt8: return decode<std::int8_t>(bytes);
      case Type::kUint8: return decode<std::uint8_t>(bytes);
      case Type::kInt16: return decode<std::int16_t>(bytes);
      case Type::kUint16: return decode<std::uint16_t>(bytes);
      case Type::kInt32: return decode<std::int32_t>(bytes);
      case Type::kUint32: return decode<std::uint32_t>(bytes);
      case Type::kFloat32: return decode<float>(bytes);
      case Type::kFloat64: return decode<double>(bytes);
    }
    return 0.0;
  }

  /// Bytes an entry of `e` takes at least: binary, its scalars and list counts; ascii, a digit
  /// and a separator per property.
  std::size_t minimumBytes(const Element& e) const {
    std::size_t bytes = 0;
    for (const Property& p : e.properties)
      bytes += encoding_ == Encoding::kAscii ? 2 : static_cast<std::size_t>(sizeOf(p.list ? p.count_type : p.type));
    return bytes;
  }
  std::size_t minimumBytes(Type item) const { return encoding_ == Encoding::kAscii ? 2 : sizeOf(item); }

 private:
  inline static const std::string kAsciiValue = "a number";
  Cursor& cursor_;
  Encoding encoding_;
};

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
};

Header readHeader(Cursor& cursor) {
  std::string_view line;
  if (!cursor.nextLine(line) || line.substr(0, 3) != "ply" ||
      line.find_first_not_of(" \t", 3) != std::string_view::npos)
    cursor.fail("the PLY magic line \"ply\"", quoted(line.substr(0, 40)));
  Header header;
  bool has_format = false;
  int entries = 0;
  while (true) {
    if (!cursor.nextLine(line)) cursor.fail("a header ending in \"end_header\"", "the end of the file");
    Cursor words(line, cursor.name(), false, cursor.line());
    std::string_view tag;
    if (!words.nextWord(tag) || tag == "comment" || tag == "obj_info") continue;
    if (tag == "end_header") break;
    if (++entries > kMaxHeaderEntries)
      cursor.fail("a header of at most " + std::to_string(kMaxHeaderEntries) + " elements and properties", "more");
    if (tag == "format") {
      std::string_view encoding;
      words.nextWord(encoding);
      if (encoding == "ascii") header.encoding = Encoding::kAscii;
      else if (encoding == "binary_little_endian") header.encoding = Encoding::kLittleEndian;
      else if (encoding == "binary_big_endian") header.encoding = Encoding::kBigEndian;
      else cursor.fail("format ascii, binary_little_endian or binary_big_endian", quoted(encoding));
      has_format = true;
    } else if (tag == "element") {
      std::string_view name, count;
      Element e;
      if (!words.nextWord(name) || !words.nextWord(count) || !parseInteger(count, e.count) || e.count < 0)
        cursor.fail("\"element <name> <count>\" with a count >= 0", quoted(line));
      e.name = std::string(name);
      header.elements.push_back(std::move(e));
    } else if (tag == "property") {
      if (header.elements.empty()) cursor.fail("an element before its properties", quoted(line));
      Property p;
      std::string_view type, name;
      if (!words.nextWord(type)) cursor.fail("\"property <type> <name>\"", quoted(line));
      if (type == "list") {
        std::string_view count_type;
        p.list = true;
        if (!words.nextWord(count_type) || !typeOf(count_type, p.count_type) || !words.nextWord(type))
          cursor.fail("\"property list <count type> <item type> <name>\" with PLY types", quoted(line));
      }
      if (!typeOf(type, p.type) || !words.nextWord(name))
        cursor.fail("\"property <type> <name>\" with a PLY type (char, uchar, short, ushort, int, uint, float, double)",
                    quoted(line));
      p.name = std::string(name);
      header.elements.back().properties.push_back(std::move(p));
    } else {
      cursor.fail("a header line format, element, property, comment, obj_info or end_header", quoted(tag));
    }
  }
  if (!has_format) cursor.fail("a \"format\" line in the header", "none before end_header");
  return header;
}

}  // namespace

PolygonSoup readPly(std::string_view bytes, const std::string& name) {
  Cursor cursor(bytes, name, /*lone_cr_ends_line=*/false);
  const Header header = readHeader(cursor);
  Values values(cursor, header.encoding);
  SoupBuilder soup(cursor);
  if (header.encoding != Encoding::kAscii) cursor.placeByByte();  // messages name the byte, not the line

  // Before allocating: every element's entries fit in the bytes after the header.
  long double needed = 0.0L;
  for (const Element& e : header.elements) {
    needed += static_cast<long double>(e.count) * static_cast<long double>(values.minimumBytes(e));
    if (needed > static_cast<long double>(cursor.remaining()) + 1.0L)  // + 1: no line end after the last value
      cursor.fail("element counts that fit in the file (an entry of '" + e.name + "' takes at least " +
                      std::to_string(values.minimumBytes(e)) + " bytes)",
                  "a header announcing " + std::to_string(e.count) + " elements '" + e.name + "' in a file of " +
                      std::to_string(cursor.size()) + " bytes");
  }

  std::vector<long long> polygon;
  for (const Element& e : header.elements) {
    if (e.properties.empty()) continue;  // nothing to read, however many
    const bool vertex = e.name == "vertex", face = e.name == "face";
    int axis_of[3] = {-1, -1, -1};  // the property index of x, y, z
    if (vertex) {
      for (std::size_t k = 0; k < e.properties.size(); ++k)
        for (int axis = 0; axis < 3; ++axis)
          if (!e.properties[k].list && e.properties[k].name == std::string(1, static_cast<char>('x' + axis)))
            axis_of[axis] = static_cast<int>(k);
      if (axis_of[0] < 0 || axis_of[1] < 0 || axis_of[2] < 0)
        cursor.fail("a vertex element with scalar properties x, y and z", "the header without them");
      soup.expectVertices(e.count);
    }
    for (long long i = 0; i < e.count; ++i) {
      double xyz[3] = {0.0, 0.0, 0.0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.list) {
          const double value = values.next(p.type);
          for (int axis = 0; axis < 3; ++axis)
            if (axis_of[axis] == static_cast<int>(k)) xyz[axis] = value;
          continue;
        }
        const double count = values.next(p.count_type);
        // Before reading the list: its items fit in the rest of the file.
        if (!(count >= 0.0 && count == std::floor(count) &&
              count * static_cast<double>(values.minimumBytes(p.type)) <= static_cast<double>(cursor.remaining()) + 1.0))
          cursor.fail("a list length that fits in the rest of the file (" + std::to_string(cursor.remaining()) + " bytes)",
                      numberText(count));
        const bool indices = face && (p.name == "vertex_indices" || p.name == "vertex_index");
        polygon.clear();
        for (long long item = 0; item < static_cast<long long>(count); ++item) {
          const double value = values.next(p.type);
          if (!indices) continue;
          if (!(value == std::floor(value) && std::abs(value) < 9.0e15))
            cursor.fail("integer vertex indices", numberText(value));
          polygon.push_back(static_cast<long long>(value));
        }
        if (indices) soup.addPolygon(polygon);
      }
      if (vertex) soup.addVertex(xyz[0], xyz[1], xyz[2]);
    }
  }
  return soup.finish();
}

}  // namespace filum::geometry::mesh_parsing
