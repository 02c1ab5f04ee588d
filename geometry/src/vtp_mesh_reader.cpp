// VTK XML PolyData (.vtp; VTK's file format description, "XML File Formats": the format 3D
// Slicer, VMTK and ParaView write segmented vessel surfaces in): <VTKFile type="PolyData"> with
// one <Piece NumberOfPoints="V" NumberOfPolys="F" NumberOfStrips="S">, the points in
// <Points><DataArray NumberOfComponents="3"> and the cells in <Polys> (polygons, fanned into
// triangles) and <Strips> (triangle strips) as two DataArrays each, "connectivity" (the corners of
// every cell, one after another) and "offsets" (where each cell ends in it).
// DataArrays inline, in format="ascii" (whitespace-separated numbers) or format="binary" (base64
// of a header, the byte count as UInt32 or UInt64 by the file's header_type, then the values in
// the file's byte_order), of types Float32/Float64 (points) and Int8..UInt64 (indices); elements
// after the data inside a DataArray (VTK's <InformationKey> of the array's ranges) are skipped.
// Or format="appended" (VTK's writers' default): the array's data at its offset="n" in the file's
// <AppendedData encoding="raw" | "base64">, after the XML. Either binary kind may be compressed
// by zlib (compressor="vtkZLibDataCompressor", VTK's default: the header then lists the blocks and
// their compressed sizes, arrayBytes); other compressors (LZ4, LZMA) are refused with how to save
// the file instead. Verts and lines are ignored (a surface is its polys and strips).
// The XML is scanned, not validated: only the elements above are looked for.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <zlib.h>

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
    Cursor at(std::string_view(), cursor_.name(), true, lineOf(offset));
    at.fail(expected, found);
  }
  /// The line of a byte (1-based; LF, CRLF and a lone CR end a line).
  long lineOf(std::size_t offset) const {
    long line = 1;
    for (std::size_t i = 0; i < offset && i < bytes_.size(); ++i)
      line += bytes_[i] == '\n' || (bytes_[i] == '\r' && (i + 1 >= bytes_.size() || bytes_[i + 1] != '\n'));
    return line;
  }
  /// The first byte at or after `from` that is not white space (where an array's values start).
  std::size_t firstValue(std::size_t from) const {
    const std::size_t at = bytes_.find_first_not_of(" \t\r\n", from);
    return at == std::string_view::npos ? from : at;
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
  bool zlib = false;                   // compressor="vtkZLibDataCompressor"
  std::string_view whole;              // the whole file (appended data lies after the XML)
  std::size_t appended = std::string_view::npos;  // where <AppendedData>'s data starts in it (after its '_')
  bool appended_base64 = false;        // <AppendedData encoding="base64"> (else "raw")
  int word() const { return header64 ? 8 : 4; }
};

/// Binary data read in order: raw bytes, or base64 (RFC 4648) decoded as it goes. VTK encodes a
/// header and the data after it as separate base64 pieces, each padded: '=' ends a group.
class ByteSource {
 public:
  /// Messages name `where` (an offset of the XML: the array's tag or its inline data) and `what`.
  ByteSource(const VtpScanner& scan, std::string_view text, std::size_t at, bool base64, std::size_t where,
             std::string what)
      : scan_(scan), text_(text), at_(at), base64_(base64), where_(where), what_(std::move(what)) {}
  /// Appends the next n bytes to out; fails naming the array when the data ends first.
  void take(std::size_t n, std::vector<unsigned char>& out) {
    if (!base64_) {
      if (at_ > text_.size() || n > text_.size() - at_)
        scan_.failAt(where_, what_ + ": " + std::to_string(n) + " more bytes of data",
                     std::to_string(at_ > text_.size() ? 0 : text_.size() - at_));
      out.insert(out.end(), text_.begin() + static_cast<std::ptrdiff_t>(at_),
                 text_.begin() + static_cast<std::ptrdiff_t>(at_ + n));
      at_ += n;
      return;
    }
    for (std::size_t got = 0; got < n;) {
      if (pending_ == pending_size_ && !decodeGroup())
        scan_.failAt(where_, what_ + ": " + std::to_string(n) + " bytes of base64 data",
                     std::to_string(got));
      for (; pending_ < pending_size_ && got < n; ++got) out.push_back(group_[pending_++]);
    }
  }

 private:
  /// The next group of up to 4 characters into 1 to 3 bytes; false at the end of the text or of
  /// the data (a '<').
  bool decodeGroup() {
    std::array<int, 4> quad{};
    int filled = 0;
    for (; at_ < text_.size() && filled < 4; ++at_) {
      const char c = text_[at_];
      int v;
      if (c >= 'A' && c <= 'Z') v = c - 'A';
      else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
      else if (c >= '0' && c <= '9') v = c - '0' + 52;
      else if (c == '+') v = 62;
      else if (c == '/') v = 63;
      else if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
      else if (c == '=' || c == '<') {
        if (filled == 0) {
          if (c == '<') return false;
          continue;  // the rest of a group's padding
        }
        break;  // the group ends (padding, or the data's end)
      } else {
        scan_.failAt(where_, what_ + ": base64 data", quoted(std::string_view(&c, 1)));
      }
      quad[filled++] = v;
    }
    if (filled == 0) return false;
    if (filled == 1) scan_.failAt(where_, what_ + ": base64 groups of 2 to 4 characters", "1");
    pending_ = 0;
    pending_size_ = filled - 1;
    group_[0] = static_cast<unsigned char>((quad[0] << 2) | (quad[1] >> 4));
    group_[1] = static_cast<unsigned char>(((quad[1] & 15) << 4) | (quad[2] >> 2));
    group_[2] = static_cast<unsigned char>(((quad[2] & 3) << 6) | quad[3]);
    return true;
  }

  const VtpScanner& scan_;
  std::string_view text_;
  std::size_t at_;
  bool base64_;
  std::size_t where_;
  std::string what_;
  std::array<unsigned char, 3> group_{};
  int pending_ = 0, pending_size_ = 0;
};

/// An unsigned integer of `size` bytes at `at` in the file's byte order.
unsigned long long unsignedAt(const std::vector<unsigned char>& bytes, std::size_t at, int size, bool big_endian) {
  unsigned long long value = 0;
  for (int b = 0; b < size; ++b) value = (value << 8) | bytes[at + (big_endian ? b : size - 1 - b)];
  return value;
}

/// A DataArray's bytes after its header: `header` + the values, or zlib blocks inflated. VTK's
/// compressed layout (vtkZLibDataCompressor): a header of words [blocks, block size, last block's
/// size (0: a full one), compressed size of each block], then the compressed blocks. The size the
/// data will have is checked against `max_bytes` before anything is allocated for it.
std::vector<unsigned char> arrayBytes(const VtpScanner& scan, ByteSource& source, const Encoding& encoding,
                                      unsigned long long max_bytes, std::size_t where, const std::string& what) {
  const int w = encoding.word();
  std::vector<unsigned char> header;
  source.take(static_cast<std::size_t>(w), header);
  const unsigned long long first = unsignedAt(header, 0, w, encoding.big_endian);
  std::vector<unsigned char> data;
  if (!encoding.zlib) {
    if (first > max_bytes)
      scan.failAt(where, what + " of at most " + std::to_string(max_bytes) + " bytes (as the Piece's counts say)",
                  std::to_string(first));
    source.take(static_cast<std::size_t>(first), data);
    return data;
  }
  const unsigned long long blocks = first;
  // Every block but an empty array's compresses to at least a byte: no more blocks than bytes.
  if (blocks > max_bytes + 1)
    scan.failAt(where, what + ": at most " + std::to_string(max_bytes + 1) + " compressed blocks", std::to_string(blocks));
  source.take(static_cast<std::size_t>(w) * static_cast<std::size_t>(2 + blocks), header);
  const unsigned long long block_size = unsignedAt(header, static_cast<std::size_t>(w), w, encoding.big_endian);
  const unsigned long long last = unsignedAt(header, 2 * static_cast<std::size_t>(w), w, encoding.big_endian);
  if (blocks > 0 && (block_size == 0 || last > block_size))
    scan.failAt(where, what + ": a block size > 0 and a last block no larger", std::to_string(block_size) + " and " +
                                                                                  std::to_string(last));
  const unsigned long long final_size = last == 0 ? block_size : last;
  // The inflated size, (blocks − 1) block_size + final_size, against max_bytes without overflow.
  if (blocks > 0 && (final_size > max_bytes || blocks - 1 > (max_bytes - final_size) / block_size))
    scan.failAt(where, what + " of at most " + std::to_string(max_bytes) + " bytes (as the Piece's counts say)",
                std::to_string(blocks) + " blocks of " + std::to_string(block_size) + " bytes once inflated");
  // Block by block: its compressed bytes taken (they exist) before its inflated size is allocated,
  // which deflate bounds at about 1032 times them.
  std::vector<unsigned char> compressed;
  for (unsigned long long b = 0; b < blocks; ++b) {
    const unsigned long long size = unsignedAt(header, static_cast<std::size_t>(w) * (3 + b), w, encoding.big_endian);
    const uLong expected = static_cast<uLong>(b + 1 == blocks ? final_size : block_size);  // <= max_bytes
    if (size > compressBound(expected))
      scan.failAt(where, what + ": zlib block " + std::to_string(b) + " of at most " + std::to_string(compressBound(expected)) +
                             " bytes (zlib's bound for " + std::to_string(expected) + ")",
                  std::to_string(size));
    compressed.clear();
    source.take(static_cast<std::size_t>(size), compressed);
    const std::size_t filled = data.size();
    data.resize(filled + expected);
    uLongf out = expected;
    const int status = uncompress(data.data() + filled, &out, compressed.data(), static_cast<uLong>(compressed.size()));
    if (status != Z_OK || out != expected)
      scan.failAt(where, what + ": zlib block " + std::to_string(b) + " inflating to " + std::to_string(expected) + " bytes",
                  status == Z_OK ? std::to_string(out) + " bytes" : std::string("zlib error ") + std::to_string(status));
  }
  return data;
}

/// The values of one DataArray as doubles (indices too: exact below 2^53, and checked as
/// integers by the caller), at most `limit` of them.
std::vector<double> dataArray(const VtpScanner& scan, const Tag& tag, const Encoding& encoding, long long limit,
                              const std::string& what) {
  const std::string_view format = VtpScanner::attribute(tag.attributes, "format");
  const std::string_view type = VtpScanner::attribute(tag.attributes, "type");
  // The data: up to the first element inside the array (VTK writes an <InformationKey> of its
  // ranges after it) or its end.
  const std::size_t stop = tag.empty ? tag.content : std::min(scan.end("DataArray", tag.content),
                                                             scan.bytes().find('<', tag.content));
  const std::string_view text = scan.bytes().substr(tag.content, stop - tag.content);
  std::vector<double> out;
  if (format == "ascii") {
    Cursor words(text, scan.cursor().name(), true, scan.lineOf(tag.content));  // messages at the value's line
    std::string_view word;
    while (words.nextWord(word)) {
      if (static_cast<long long>(out.size()) >= limit)
        words.fail(what + " of at most " + std::to_string(limit) + " values (as the Piece's counts say)", "more");
      double value = 0.0;
      if (!parseNumber(word, value)) words.fail(what + ": numbers", quoted(word));
      out.push_back(value);
    }
    return out;
  }
  if (format != "binary" && format != "appended")
    scan.failAt(tag.content, what + " in format \"ascii\", \"binary\" or \"appended\"",
                quoted(format.empty() ? "none" : format));
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
  const unsigned long long max_bytes = static_cast<unsigned long long>(limit) * static_cast<unsigned long long>(t->size);
  std::vector<unsigned char> bytes;
  if (format == "binary") {  // inline base64: the header, then the values (or the zlib blocks)
    ByteSource source(scan, scan.bytes().substr(0, stop), tag.content, true, tag.content, what);
    bytes = arrayBytes(scan, source, encoding, max_bytes, tag.content, what);
  } else {  // in <AppendedData>, at the array's offset from the '_' that starts its data
    if (encoding.appended == std::string_view::npos)
      scan.failAt(tag.start, what + " in the file's <AppendedData> (format=\"appended\")", "no <AppendedData>");
    long long offset = -1;
    const std::string_view offset_text = VtpScanner::attribute(tag.attributes, "offset");
    const std::size_t available = encoding.whole.size() - encoding.appended;
    if (!parseInteger(offset_text, offset) || offset < 0 || static_cast<unsigned long long>(offset) > available)
      scan.failAt(tag.start, what + ": an offset=\"n\" into the appended data (0 to " + std::to_string(available) + ")",
                  quoted(offset_text.empty() ? "none" : offset_text));
    ByteSource source(scan, encoding.whole, encoding.appended + static_cast<std::size_t>(offset), encoding.appended_base64,
                      tag.start, what);
    bytes = arrayBytes(scan, source, encoding, max_bytes, tag.start, what);
  }
  if (bytes.size() % static_cast<std::size_t>(t->size) != 0)
    scan.failAt(tag.content, what + ": a byte count that is a multiple of " + std::to_string(t->size) + " (" + t->name + ")",
                std::to_string(bytes.size()));
  const std::size_t n = bytes.size() / static_cast<std::size_t>(t->size);
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned long long bits = unsignedAt(bytes, i * static_cast<std::size_t>(t->size), t->size, encoding.big_endian);
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
    scan.failAt(piece.start, "a count " + std::string(key) + "=\"n\" (n >= 0) on the Piece", quoted(text));
  return value;
}

/// The cells of <Polys> or <Strips>: each cell's corners, checked before a triangle is made:
/// offsets whole numbers growing by at least 3 (a polygon or strip of 3 or more points) up to
/// the connectivity's size, indices of points in [0, V).
struct Cells {
  std::vector<double> offsets, connectivity;
};

Cells readCells(const VtpScanner& scan, const std::string& element, std::size_t from, std::size_t until, long long count,
                long long vertex_count, const Encoding& encoding) {
  const Tag block = scan.tag(element, from, until, "the <" + element + "> of the Piece (its count is not 0)");
  const std::size_t block_end = scan.end(element, block.content);
  const std::string cells = "the " + element + "' ";
  const Tag offsets_tag = namedArray(scan, block.content, block_end, "offsets", cells + "\"offsets\" <DataArray>");
  Cells c;
  c.offsets = dataArray(scan, offsets_tag, encoding, count, cells + "offsets");
  const std::size_t offsets_at = scan.firstValue(offsets_tag.content);
  if (static_cast<long long>(c.offsets.size()) != count)
    scan.failAt(offsets_at, std::to_string(count) + " offsets (the Piece's count)", std::to_string(c.offsets.size()));
  // The connectivity's size is the last offset: at least 3 corners a cell, and at most the
  // corners of the kMaxMeshTriangles triangles they may give (a cell of n corners gives n − 2
  // triangles: corners <= triangles + 2 F).
  const double corners = c.offsets.back();
  if (!(corners >= 3.0 * static_cast<double>(count)) ||
      corners > static_cast<double>(kMaxMeshTriangles) + 2.0 * static_cast<double>(count))
    scan.failAt(offsets_at, "a last offset of at least 3 × the count and at most the corners of " +
                                std::to_string(kMaxMeshTriangles) + " triangles",
                numberText(corners));
  double begin = 0.0;
  for (long long f = 0; f < count; ++f) {
    const double end = c.offsets[static_cast<std::size_t>(f)];
    if (!(end >= begin + 3.0) || end > corners || end != std::floor(end))
      scan.failAt(offsets_at, "offsets that are whole numbers growing by at least 3 (a cell of 3 or more points)",
                  "offset " + std::to_string(f) + " = " + numberText(end) + " after " + numberText(begin));
    begin = end;
  }
  const Tag connectivity_tag =
      namedArray(scan, block.content, block_end, "connectivity", cells + "\"connectivity\" <DataArray>");
  c.connectivity = dataArray(scan, connectivity_tag, encoding, static_cast<long long>(corners), cells + "connectivity");
  const std::size_t connectivity_at = scan.firstValue(connectivity_tag.content);
  if (static_cast<double>(c.connectivity.size()) != corners)
    scan.failAt(connectivity_at, "a connectivity of " + numberText(corners) + " indices (the last offset)",
                std::to_string(c.connectivity.size()));
  for (const double index : c.connectivity)
    if (!(index >= 0.0 && index < static_cast<double>(vertex_count)) || index != std::floor(index))
      scan.failAt(connectivity_at,
                  "indices of points in the connectivity (whole numbers in [0, " + std::to_string(vertex_count) + "))",
                  numberText(index));
  return c;
}

}  // namespace

PolygonSoup readVtp(std::string_view bytes, const std::string& name) {
  // The XML is all before <AppendedData> (VTK writes it last, its binary data after it): it alone
  // is scanned for elements, so that no search runs into binary bytes.
  const std::size_t appended_at = bytes.find("<AppendedData");
  const VtpScanner scan(bytes.substr(0, appended_at), name);
  SoupBuilder soup(scan.cursor());  // every check it makes is made before, at its place
  const std::size_t all = bytes.size();
  const Tag file = scan.tag("VTKFile", 0, all, "a VTK XML file (<VTKFile type=\"PolyData\" ...>)");
  if (VtpScanner::attribute(file.attributes, "type") != "PolyData")
    scan.failAt(file.start, "a PolyData file (<VTKFile type=\"PolyData\">)",
                quoted(VtpScanner::attribute(file.attributes, "type")));
  Encoding encoding;
  const std::string_view compressor = VtpScanner::attribute(file.attributes, "compressor");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    scan.failAt(file.start,
                "data compressed by zlib (vtkZLibDataCompressor, VTK's default) or not at all (ParaView: save with "
                "Compressor ZLib or None; VTK: SetCompressorTypeToZLib)",
                "compressor=\"" + std::string(compressor) + "\"");
  encoding.zlib = !compressor.empty();
  const std::string_view byte_order = VtpScanner::attribute(file.attributes, "byte_order");
  if (!byte_order.empty() && byte_order != "LittleEndian" && byte_order != "BigEndian")
    scan.failAt(file.start, "byte_order \"LittleEndian\" or \"BigEndian\"", quoted(byte_order));
  encoding.big_endian = byte_order == "BigEndian";
  const std::string_view header_type = VtpScanner::attribute(file.attributes, "header_type");
  if (!header_type.empty() && header_type != "UInt32" && header_type != "UInt64")
    scan.failAt(file.start, "header_type \"UInt32\" or \"UInt64\"", quoted(header_type));
  encoding.header64 = header_type == "UInt64";

  // Appended data (VTK's default): after the XML, in <AppendedData encoding="raw" | "base64">,
  // from the '_' that marks its start (after white space).
  if (appended_at != std::string_view::npos) {
    const VtpScanner whole(bytes, name);
    const Tag appended = whole.tag("AppendedData", appended_at, all, "<AppendedData>");
    const std::string_view kind = VtpScanner::attribute(appended.attributes, "encoding");
    if (kind != "raw" && kind != "base64")
      whole.failAt(appended.start, "<AppendedData encoding=\"raw\"> or \"base64\"", quoted(kind.empty() ? "none" : kind));
    const std::size_t mark = whole.firstValue(appended.content);
    if (mark >= all || bytes[mark] != '_')
      whole.failAt(appended.content, "the '_' that starts the appended data", mark >= all ? "the end of the file" : "other bytes");
    encoding.whole = bytes;
    encoding.appended = mark + 1;
    encoding.appended_base64 = kind == "base64";
  }
  const std::size_t xml_end = scan.bytes().size();
  const Tag piece = scan.tag("Piece", file.content, xml_end, "a <Piece NumberOfPoints=... NumberOfPolys=...>");
  const std::size_t piece_end = scan.end("Piece", piece.content);
  if (bytes.substr(0, xml_end).find("<Piece", piece_end) != std::string_view::npos)
    scan.failAt(piece_end, "one Piece (a surface merged into one: VTK's vtkAppendPolyData)", "more than one");
  const long long vertex_count = count(scan, piece, "NumberOfPoints");
  const long long polygon_count = count(scan, piece, "NumberOfPolys");
  const long long strip_count = count(scan, piece, "NumberOfStrips");
  if (polygon_count == 0 && strip_count == 0)
    scan.failAt(piece.start, "polygons or triangle strips (NumberOfPolys or NumberOfStrips > 0): a surface", "none");
  if (vertex_count < 3 || vertex_count > kMaxMeshVertices)
    scan.failAt(piece.start, "NumberOfPoints from 3 to " + std::to_string(kMaxMeshVertices), std::to_string(vertex_count));
  if (polygon_count > kMaxMeshTriangles || strip_count > kMaxMeshTriangles)
    scan.failAt(piece.start, "at most " + std::to_string(kMaxMeshTriangles) + " cells of each kind",
                std::to_string(std::max(polygon_count, strip_count)));

  // Points: 3 V finite coordinates (decoded before anything is allocated for V: their bytes exist).
  const Tag points = scan.tag("Points", piece.content, piece_end, "the <Points> of the Piece");
  const std::size_t points_end = scan.end("Points", points.content);
  const Tag coordinates = namedArray(scan, points.content, points_end, "", "the points' <DataArray>");
  const std::string_view components = VtpScanner::attribute(coordinates.attributes, "NumberOfComponents");
  if (components != "3") scan.failAt(coordinates.start, "points of NumberOfComponents=\"3\"", quoted(components));
  const std::vector<double> xyz = dataArray(scan, coordinates, encoding, 3 * vertex_count, "the points");
  const std::size_t xyz_at = scan.firstValue(coordinates.content);
  if (static_cast<long long>(xyz.size()) != 3 * vertex_count)
    scan.failAt(xyz_at, std::to_string(3 * vertex_count) + " coordinates (NumberOfPoints × 3)", std::to_string(xyz.size()));
  for (std::size_t k = 0; k < xyz.size(); ++k)
    if (!std::isfinite(xyz[k]))
      scan.failAt(xyz_at, "finite coordinates", "coordinate " + std::to_string(k) + " = " + numberText(xyz[k]));
  soup.expectVertices(vertex_count);
  for (long long i = 0; i < vertex_count; ++i) soup.addVertex(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  // Polygons, fanned (v0, v_k, v_{k+1}); strips, triangle k of a strip p_0 p_1 ... being
  // (p_k, p_{k+1}, p_{k+2}) for even k and (p_{k+1}, p_k, p_{k+2}) for odd k, so that the strip's
  // triangles keep one orientation.
  std::vector<long long> polygon;
  if (polygon_count > 0) {
    const Cells polys = readCells(scan, "Polys", piece.content, piece_end, polygon_count, vertex_count, encoding);
    std::size_t begin = 0;
    for (const double end : polys.offsets) {
      polygon.assign(polys.connectivity.begin() + static_cast<std::ptrdiff_t>(begin),
                     polys.connectivity.begin() + static_cast<std::ptrdiff_t>(end));
      soup.addPolygon(polygon);
      begin = static_cast<std::size_t>(end);
    }
  }
  if (strip_count > 0) {
    const Cells strips = readCells(scan, "Strips", piece.content, piece_end, strip_count, vertex_count, encoding);
    std::size_t begin = 0;
    for (const double end : strips.offsets) {
      const auto p = [&](std::size_t k) { return static_cast<long long>(strips.connectivity[begin + k]); };
      for (std::size_t k = 0; begin + k + 2 < static_cast<std::size_t>(end); ++k) {
        if (p(k) == p(k + 1) || p(k + 1) == p(k + 2) || p(k) == p(k + 2)) continue;  // a join of strips
        if (k % 2 == 0)
          polygon = {p(k), p(k + 1), p(k + 2)};
        else
          polygon = {p(k + 1), p(k), p(k + 2)};
        soup.addPolygon(polygon);
      }
      begin = static_cast<std::size_t>(end);
    }
  }
  return soup.finish();
}

}  // namespace filum::geometry::mesh_parsing
