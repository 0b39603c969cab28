#include "scenes/mesh_file_check.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <vector>

namespace oit {
namespace {

// A face with more corners than this is treated as corrupt: no real mesh has
// one, and OpenMesh would build a handle vector of that size.
constexpr uint64_t kMaxFaceCorners = 1u << 16;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// The lines of a text file (or of a PLY header), trimmed and numbered from
// 1. Reading past the end gives empty lines and still counts them, so a
// message about a missing line names the line that is missing.
class TextLines {
 public:
  explicit TextLines(std::string_view bytes) : bytes_(bytes) {}
  // The next line; false (and an empty line) once the bytes are used up.
  bool next(std::string_view& line) {
    ++number_;
    if (start_ >= bytes_.size()) {
      line = {};
      return false;
    }
    size_t end = bytes_.find('\n', start_);
    if (end == std::string_view::npos) end = bytes_.size();
    line = trim(bytes_.substr(start_, end - start_));
    start_ = end + 1;
    return true;
  }
  uint64_t number() const { return number_; }     // of the line last read
  std::string_view rest() const { return bytes_.substr(std::min(start_, bytes_.size())); }

 private:
  std::string_view bytes_;
  size_t start_ = 0;
  uint64_t number_ = 0;
};

std::string shown(std::string_view token) {
  std::string text(token.substr(0, 32));
  for (char& c : text)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return "'" + text + (token.size() > 32 ? "...'" : "'");
}

// Whitespace-separated tokens the way std::istream >> reads them.
class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}
  std::string_view next() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  // Past the next line end, like std::getline after a >> extraction.
  void skip_line() {
    const size_t end = text_.find('\n', pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  }
  size_t remaining() const { return text_.size() - pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
};

enum class Parsed { ok, missing, malformed, non_finite, out_of_range };

// A decimal number as stream extraction of a float reads it. Words such as
// nan/inf and hexadecimal forms are refused: the stream would fail on them
// and OpenMesh would silently lose or shift the vertex.
Parsed parse_real(std::string_view token, double& value) {
  if (token.empty()) return Parsed::missing;
  std::string lower(token);
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos) return Parsed::non_finite;
  if (lower.find_first_not_of("0123456789+-.e") != std::string::npos) return Parsed::malformed;
  char* end = nullptr;
  value = std::strtod(lower.c_str(), &end);
  if (end != lower.c_str() + lower.size()) return Parsed::malformed;
  if (!std::isfinite(value)) return Parsed::non_finite;
  if (std::abs(value) > double(FLT_MAX)) return Parsed::out_of_range;  // would become inf as a float
  return Parsed::ok;
}

Parsed parse_unsigned(std::string_view token, uint64_t& value) {
  if (token.empty()) return Parsed::missing;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error == std::errc::result_out_of_range) return Parsed::out_of_range;
  if (error != std::errc() || end != token.data() + token.size()) return Parsed::malformed;
  return Parsed::ok;
}

Parsed parse_signed(std::string_view token, int64_t& value) {
  if (token.empty()) return Parsed::missing;
  if (token.front() == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error == std::errc::result_out_of_range) return Parsed::out_of_range;
  if (error != std::errc() || end != token.data() + token.size()) return Parsed::malformed;
  return Parsed::ok;
}

std::string problem(Parsed parsed, std::string_view token, const std::string& what) {
  switch (parsed) {
    case Parsed::missing: return what + " is missing (file truncated?)";
    case Parsed::malformed: return what + " " + shown(token) + " is not a number";
    case Parsed::non_finite: return what + " " + shown(token) + " is not finite";
    case Parsed::out_of_range: return what + " " + shown(token) + " is out of range";
    case Parsed::ok: break;
  }
  return what;
}

double require_real(const std::string& path, std::string_view token, const std::string& what) {
  double value = 0.0;
  if (const Parsed p = parse_real(token, value); p != Parsed::ok) fail(path, problem(p, token, what));
  return value;
}

uint64_t require_unsigned(const std::string& path, std::string_view token, const std::string& what,
                          uint64_t max = UINT32_MAX) {
  uint64_t value = 0;
  Parsed p = parse_unsigned(token, value);
  if (p == Parsed::ok && value > max) p = Parsed::out_of_range;
  if (p != Parsed::ok) fail(path, problem(p, token, what));
  return value;
}

void require_index(const std::string& path, uint64_t index, uint64_t vertices, const std::string& where) {
  if (index >= vertices)
    fail(path, where + " references vertex " + std::to_string(index) + ", but there are only " +
                   std::to_string(vertices) + " vertices");
}

// Refuses a declared count that the remaining bytes cannot hold at
// `min_bytes` each, before any loop runs that long.
void require_room(const std::string& path, uint64_t count, uint64_t min_bytes, size_t remaining,
                  const std::string& what) {
  if (min_bytes > 0 && count > remaining / min_bytes)
    fail(path, "declares " + std::to_string(count) + " " + what + ", but only " + std::to_string(remaining) +
                   " bytes follow (file truncated or count corrupt)");
}

// ---------------------------------------------------------------- OBJ

MeshFileFacts check_obj(const std::string& path, std::string_view bytes) {
  MeshFileFacts facts{"obj"};
  uint64_t largest_positive = 0, largest_line = 0;
  TextLines lines(bytes);
  std::string_view line;
  while (lines.next(line)) {
    const uint64_t line_number = lines.number();
    if (line.empty() || line.front() == '#') continue;
    const std::string at = "line " + std::to_string(line_number);
    Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    if (keyword == "v") {
      for (const char* axis : {"x", "y", "z"}) require_real(path, tokens.next(), at + ": vertex " + axis);
      ++facts.vertices;
    } else if (keyword == "f") {
      uint64_t corners = 0;
      for (std::string_view corner = tokens.next(); !corner.empty(); corner = tokens.next()) {
        // v, v/vt, v/vt/vn or v//vn: the position index comes first and must be there.
        const std::string_view position = corner.substr(0, corner.find('/'));
        int64_t index = 0;
        const Parsed p = parse_signed(position, index);
        if (p != Parsed::ok || index < INT32_MIN / 2 || index > INT32_MAX / 2) {
          fail(path, at + ": face corner " + shown(corner) + " has no valid vertex index");
        }
        if (index == 0) fail(path, at + ": vertex index 0 (OBJ indices start at 1)");
        if (index < 0 && uint64_t(-index) > facts.vertices) {
          fail(path, at + ": relative vertex index " + std::to_string(index) + " reaches before the first vertex");
        }
        if (index > 0 && uint64_t(index) > largest_positive) {
          largest_positive = uint64_t(index);
          largest_line = line_number;
        }
        if (++corners > kMaxFaceCorners) fail(path, at + ": face has more than " + std::to_string(kMaxFaceCorners) + " corners");
      }
      if (corners < 3) fail(path, at + ": face has " + std::to_string(corners) + " corners; at least 3 are needed");
      ++facts.faces;
    } else if (keyword == "mtllib") {
      // OpenMesh opens the material library relative to the file and reads
      // it line by line: a device or directory there would never end.
      const std::filesystem::path library =
          std::filesystem::path(path).parent_path() / std::string(trim(line.substr(6)));
      std::error_code error;
      if (std::filesystem::exists(library, error) && !std::filesystem::is_regular_file(library, error))
        fail(path, at + ": material library " + shown(library.string()) + " is not a regular file");
    }
  }
  if (largest_positive > facts.vertices) {
    fail(path, "line " + std::to_string(largest_line) + ": face references vertex " + std::to_string(largest_positive) +
                   ", but the file defines only " + std::to_string(facts.vertices) + " vertices");
  }
  return facts;
}

// ---------------------------------------------------------------- OFF

MeshFileFacts check_off(const std::string& path, std::string_view bytes) {
  MeshFileFacts facts{"off"};
  const size_t header_end = std::min(bytes.find('\n'), bytes.size());
  std::string_view header = trim(bytes.substr(0, header_end));
  // [ST][C][N][4][n]OFF [BINARY], as OpenMesh reads the first line.
  bool normals = false, colors = false;
  if (header.substr(0, 2) == "ST") header.remove_prefix(2);
  if (!header.empty() && header.front() == 'C') colors = true, header.remove_prefix(1);
  if (!header.empty() && header.front() == 'N') normals = true, header.remove_prefix(1);
  if (!header.empty() && (header.front() == '4' || header.front() == 'n'))
    fail(path, "4D and nD OFF files are not supported");
  if (header.substr(0, 3) != "OFF") fail(path, "does not start with an OFF header line");
  const std::string_view rest = trim(header.substr(3));
  if (rest.substr(0, 6) == "BINARY") fail(path, "binary OFF is not supported (convert it to ASCII OFF)");
  if (!rest.empty()) fail(path, "unexpected " + shown(rest) + " after OFF on the first line (counts go on the next line)");
  (void)colors;  // colours and texture coordinates sit in the rest of each line, which OpenMesh reads as a whole

  Tokens tokens(bytes.substr(std::min(header_end + 1, bytes.size())));
  facts.vertices = require_unsigned(path, tokens.next(), "vertex count");
  facts.faces = require_unsigned(path, tokens.next(), "face count");
  require_unsigned(path, tokens.next(), "edge count");
  // At least "0 0 0" per vertex and "3 0 1 2" per face, each after a line end.
  require_room(path, facts.vertices, 6, tokens.remaining(), "vertices");
  for (uint64_t v = 0; v < facts.vertices; ++v) {
    const std::string at = "vertex " + std::to_string(v);
    for (const char* axis : {"x", "y", "z"}) require_real(path, tokens.next(), at + " " + axis);
    if (normals)
      for (const char* axis : {"x", "y", "z"}) require_real(path, tokens.next(), at + " normal " + axis);
    tokens.skip_line();
  }
  require_room(path, facts.faces, 7, tokens.remaining(), "faces");
  for (uint64_t f = 0; f < facts.faces; ++f) {
    const std::string at = "face " + std::to_string(f);
    const uint64_t corners = require_unsigned(path, tokens.next(), at + " corner count", kMaxFaceCorners);
    if (corners < 3) fail(path, at + " has " + std::to_string(corners) + " corners; at least 3 are needed");
    require_room(path, corners, 2, tokens.remaining(), "corners in " + at);
    for (uint64_t c = 0; c < corners; ++c)
      require_index(path, require_unsigned(path, tokens.next(), at + " corner " + std::to_string(c)), facts.vertices, at);
    if (colors) tokens.skip_line();
  }
  return facts;
}

// ---------------------------------------------------------------- PLY

struct PlyType {
  int bytes = 0;
  bool integer = false;
  bool is_signed = false;
};

struct PlyProperty {
  std::string name;
  PlyType type;
  bool list = false;
  PlyType count_type;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

bool ply_type(std::string_view name, PlyType& type) {
  static const std::map<std::string, PlyType, std::less<>> types = {
      {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, true, false}},
      {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
      {"ushort", {2, true, false}}, {"uint16", {2, true, false}},  {"int", {4, true, true}},
      {"int32", {4, true, true}},   {"uint", {4, true, false}},    {"uint32", {4, true, false}},
      {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
      {"float64", {8, false, true}}};
  const auto it = types.find(name);
  if (it == types.end()) return false;
  type = it->second;
  return true;
}

bool is_index_list(const std::string& name) { return name == "vertex_indices" || name == "vertex_index"; }

// Reads values of the body, binary or ASCII, each bounded by what is left.
class PlyBody {
 public:
  PlyBody(const std::string& path, std::string_view body, bool binary, bool big_endian)
      : path_(path), body_(body), tokens_(body), binary_(binary), big_endian_(big_endian) {}

  size_t remaining() const { return binary_ ? body_.size() - pos_ : tokens_.remaining(); }

  double real(const PlyType& type, const std::string& what) {
    if (!binary_) {
      const std::string_view token = tokens_.next();
      if (type.integer) return double(integer_token(token, type, what));
      return require_real(path_, token, what);
    }
    if (type.integer) return double(integer(type, what));
    const unsigned char* p = take(type.bytes, what);
    double value;
    if (type.bytes == 4) {
      float f;
      std::memcpy(&f, ordered(p, 4).data(), 4);
      value = f;
    } else {
      std::memcpy(&value, ordered(p, 8).data(), 8);
    }
    if (!std::isfinite(value) || std::abs(value) > double(FLT_MAX)) fail(path_, what + " is not finite");
    return value;
  }

  int64_t integer(const PlyType& type, const std::string& what) {
    if (!binary_) return integer_token(tokens_.next(), type, what);
    if (!type.integer) fail(path_, what + " must have an integer type");
    const auto bytes = ordered(take(type.bytes, what), type.bytes);
    uint64_t raw = 0;
    for (int i = type.bytes - 1; i >= 0; --i) raw = (raw << 8) | bytes[size_t(i)];
    if (type.is_signed && (raw >> (8 * type.bytes - 1)) & 1u) return int64_t(raw) - (int64_t(1) << (8 * type.bytes));
    return int64_t(raw);
  }

 private:
  int64_t integer_token(std::string_view token, const PlyType& type, const std::string& what) {
    int64_t value = 0;
    const Parsed p = type.integer ? parse_signed(token, value) : Parsed::malformed;
    if (p != Parsed::ok) fail(path_, problem(p, token, what + " (" + (type.integer ? "integer" : "real") + ")"));
    return value;
  }
  const unsigned char* take(int bytes, const std::string& what) {
    if (body_.size() - pos_ < size_t(bytes)) fail(path_, what + " is missing (file truncated?)");
    const auto* p = reinterpret_cast<const unsigned char*>(body_.data() + pos_);
    pos_ += size_t(bytes);
    return p;
  }
  // Little-endian copy of `bytes` (<= 8) bytes.
  std::array<unsigned char, 8> ordered(const unsigned char* p, int bytes) const {
    std::array<unsigned char, 8> out{};
    std::memcpy(out.data(), p, size_t(bytes));
    if (big_endian_) std::reverse(out.begin(), out.begin() + bytes);
    return out;
  }

  const std::string& path_;
  std::string_view body_;
  Tokens tokens_;
  size_t pos_ = 0;
  bool binary_, big_endian_;
};

struct PlyHeader {
  std::vector<PlyElement> elements;
  bool binary = false, big_endian = false;
};

// The header is text; OpenMesh's header parser loops forever on some
// control bytes (a NUL inside the format line, found by the mutation test).
void require_text_line(const std::string& path, std::string_view line, const std::string& at) {
  for (const char c : line)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || static_cast<unsigned char>(c) > 0x7e)
      fail(path, at + ": byte " + std::to_string(static_cast<unsigned char>(c)) + " in a text header");
}

// OpenMesh reads the header as a stream of words, not of lines: it takes
// the three words after "ply" as the format line whatever they are, reads
// any other unknown word as the next keyword, and a declaration missing a
// word takes the next line's first word (a property without a name is named
// "end_header"). A word that does not parse as the number it expects (a
// format version "ply") stops the stream, and its header parser then loops
// forever looking for end_header (both found by the fuzzer). So the format
// line comes second, each declaration is exactly its words, and no other
// line holds a keyword OpenMesh would act on.
std::string_view required_word(const std::string& path, Tokens& tokens, const std::string& at, const char* what) {
  const std::string_view word = tokens.next();
  if (word.empty()) fail(path, at + ": " + what + " is missing");
  return word;
}

void require_line_end(const std::string& path, Tokens& tokens, const std::string& at) {
  if (const std::string_view extra = tokens.next(); !extra.empty())
    fail(path, at + ": unexpected " + shown(extra) + " after the declaration");
}

// "format <ascii|binary_little_endian|binary_big_endian> 1.0".
void read_ply_format(const std::string& path, Tokens& tokens, const std::string& at, PlyHeader& header) {
  const std::string_view format = tokens.next();
  if (format == "ascii") header.binary = false;
  else if (format == "binary_little_endian") header.binary = true;
  else if (format == "binary_big_endian") header.binary = header.big_endian = true;
  else fail(path, at + ": unknown format " + shown(format));
  if (const std::string_view version = tokens.next(); version != "1.0")
    fail(path, at + ": format version " + shown(version) + " is not 1.0");
  require_line_end(path, tokens, at);
}

// "property <type> <name>" or "property list <count type> <type> <name>"
// of the last element declared.
void read_ply_property(const std::string& path, Tokens& tokens, const std::string& at, PlyHeader& header) {
  if (header.elements.empty()) fail(path, at + ": property before any element");
  PlyProperty property;
  std::string_view type = tokens.next();
  if (type == "list") {
    property.list = true;
    const std::string_view count_type = tokens.next();
    if (!ply_type(count_type, property.count_type) || !property.count_type.integer)
      fail(path, at + ": list count type " + shown(count_type) + " is not an integer type");
    type = tokens.next();
  }
  if (!ply_type(type, property.type)) fail(path, at + ": unknown property type " + shown(type));
  property.name = std::string(required_word(path, tokens, at, "the property name"));
  require_line_end(path, tokens, at);
  PlyElement& element = header.elements.back();
  // OpenMesh walks the lists it knows (face vertex indices and texture
  // coordinates); any other list it would read as one value and lose its
  // place in the file.
  const bool known_list = element.name == "face" && (is_index_list(property.name) || property.name == "texcoord");
  if (property.list && !known_list)
    fail(path, at + ": list property '" + property.name + "' of element '" + element.name + "' is not supported");
  if (element.name == "face" && is_index_list(property.name) && (!property.list || !property.type.integer))
    fail(path, at + ": face vertex indices must be a list of integers");
  element.properties.push_back(property);
}

// The header's lines up to end_header; `lines` is left at the body.
PlyHeader read_ply_header(const std::string& path, TextLines& lines) {
  PlyHeader header;
  bool have_format = false, ended = false;
  std::string_view line;
  while (!ended && lines.next(line)) {
    const uint64_t line_number = lines.number();
    const std::string at = "header line " + std::to_string(line_number);
    require_text_line(path, line, at);
    Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    if (line_number == 1) {
      if (line != "ply") fail(path, "does not start with 'ply'");
    } else if (line_number == 2 || keyword == "format") {
      if (keyword != "format" || have_format) fail(path, at + ": the format line must be line 2, once");
      read_ply_format(path, tokens, at, header);
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(required_word(path, tokens, at, "the element name"));
      element.count = require_unsigned(path, tokens.next(), at + ": element count");
      require_line_end(path, tokens, at);
      for (const auto& e : header.elements)
        if (e.name == element.name) fail(path, at + ": element '" + element.name + "' is declared twice");
      header.elements.push_back(element);
    } else if (keyword == "property") {
      read_ply_property(path, tokens, at, header);
    } else if (keyword == "end_header") {
      require_line_end(path, tokens, at);
      ended = true;
    } else if (keyword != "comment") {
      // obj_info and free text (Blender writes a "Created by ..." line):
      // OpenMesh reads each word as a keyword, so none may be one it acts on.
      for (std::string_view word = tokens.next(); !word.empty(); word = tokens.next())
        if (word == "element" || word == "property" || word == "end_header")
          fail(path, at + ": the keyword " + shown(word) + " inside a " + shown(keyword) + " line");
    }
  }
  if (!ended) fail(path, "the PLY header has no end_header line");
  return header;
}

// The vertex element, with x, y and z (float or double when binary).
const PlyElement& ply_vertex_element(const std::string& path, const PlyHeader& header) {
  const PlyElement* vertex = nullptr;
  for (const auto& e : header.elements)
    if (e.name == "vertex") vertex = &e;
  if (!vertex) fail(path, "has no vertex element");
  for (const char* axis : {"x", "y", "z"}) {
    const auto& props = vertex->properties;
    const auto it = std::find_if(props.begin(), props.end(), [&](const PlyProperty& p) { return p.name == axis; });
    if (it == props.end()) fail(path, std::string("vertex element has no '") + axis + "' property");
    if (header.binary && it->type.integer)
      fail(path, std::string("binary vertex '") + axis + "' must be float or double (OpenMesh reads only those)");
  }
  return *vertex;
}

// One list property of item `at`: its count in range, and every value; a
// face's vertex indices must name one of `vertices`.
void check_ply_list(const std::string& path, PlyBody& body, const PlyProperty& p, bool is_face, bool binary,
                    uint64_t vertices, const std::string& at) {
  const int64_t count = body.integer(p.count_type, at + " " + p.name + " count");
  if (count < 0 || uint64_t(count) > kMaxFaceCorners)
    fail(path, at + ": " + p.name + " count " + std::to_string(count) + " is out of range");
  const bool indices = is_face && is_index_list(p.name);
  if (indices && count < 3) fail(path, at + " has " + std::to_string(count) + " corners; at least 3 are needed");
  require_room(path, uint64_t(count), binary ? uint64_t(p.type.bytes) : 2u, body.remaining(),
               p.name + " values in " + at);
  for (int64_t c = 0; c < count; ++c) {
    if (indices) {
      const int64_t index = body.integer(p.type, at + " corner " + std::to_string(c));
      if (index < 0) fail(path, at + " references vertex " + std::to_string(index));
      require_index(path, uint64_t(index), vertices, at);
    } else {
      body.real(p.type, at + " " + p.name);
    }
  }
}

// Every item of `element`, after checking the body can hold them. False
// when the element has no properties: it occupies nothing.
bool check_ply_element(const std::string& path, PlyBody& body, const PlyElement& element, bool binary,
                       uint64_t vertices) {
  uint64_t min_bytes = 0;  // smallest possible item: one byte (binary) or two characters (ASCII) per value
  for (const auto& p : element.properties)
    min_bytes += binary ? uint64_t(p.list ? p.count_type.bytes : p.type.bytes) : 2u;
  // (+1: the last ASCII value needs no separator after it)
  require_room(path, element.count, min_bytes, body.remaining() + (binary ? 0 : 1), element.name + " items");
  if (min_bytes == 0) return false;
  const bool is_face = element.name == "face";
  for (uint64_t i = 0; i < element.count; ++i) {
    const std::string at = element.name + " " + std::to_string(i);
    for (const auto& p : element.properties) {
      if (p.list) check_ply_list(path, body, p, is_face, binary, vertices, at);
      else body.real(p.type, at + " " + p.name);  // every scalar must parse; reals must be finite
    }
  }
  return true;
}

MeshFileFacts check_ply(const std::string& path, std::string_view bytes) {
  MeshFileFacts facts{"ply"};
  TextLines lines(bytes);
  const PlyHeader header = read_ply_header(path, lines);
  facts.vertices = ply_vertex_element(path, header).count;
  facts.binary = header.binary;
  PlyBody body(path, lines.rest(), header.binary, header.big_endian);
  for (const auto& element : header.elements) {
    if (!check_ply_element(path, body, element, header.binary, facts.vertices)) continue;
    if (element.name == "face") {
      facts.faces = element.count;
      break;  // OpenMesh stops after the faces
    }
  }
  return facts;
}

// ---------------------------------------------------------------- STL

MeshFileFacts check_stl(const std::string& path, std::string_view bytes) {
  MeshFileFacts facts{"stl"};
  // OpenMesh reads a file as binary exactly when its size is 84 + 50 * the
  // facet count in the header; anything else is parsed as ASCII.
  if (bytes.size() >= 84) {
    uint32_t declared = 0;
    std::memcpy(&declared, bytes.data() + 80, 4);
    if (uint64_t(bytes.size()) == 84 + 50 * uint64_t(declared)) {
      facts.binary = true;
      facts.faces = declared;
      facts.vertices = 3 * uint64_t(declared);
      for (uint64_t f = 0; f < declared; ++f) {
        const char* facet = bytes.data() + 84 + 50 * f;
        for (int k = 3; k < 12; ++k) {  // skip the facet normal, check the three corners
          float value;
          std::memcpy(&value, facet + 4 * k, 4);
          if (!std::isfinite(value))
            fail(path, "facet " + std::to_string(f) + " corner " + std::to_string(k / 3 - 1) + " is not finite");
        }
      }
      return facts;
    }
  }
  const std::string_view text = trim(bytes.substr(0, std::min<size_t>(bytes.size(), 512)));
  if (text.substr(0, 5) != "solid") {
    std::string detail;
    if (bytes.size() >= 84) {
      uint32_t declared = 0;
      std::memcpy(&declared, bytes.data() + 80, 4);
      detail = ": as binary STL it declares " + std::to_string(declared) + " facets = " +
               std::to_string(84 + 50 * uint64_t(declared)) + " bytes, but the file has " + std::to_string(bytes.size()) +
               " (truncated?)";
    }
    fail(path, "is neither ASCII STL (no 'solid') nor binary STL" + detail);
  }
  // ASCII: every corner is a line "vertex x y z" (OpenMesh reads three lines after "outer loop").
  TextLines lines(bytes);
  std::string_view line;
  while (lines.next(line)) {
    Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    const std::string at = "line " + std::to_string(lines.number());
    if (line.find("outer") != std::string_view::npos || line.find("OUTER") != std::string_view::npos) {
      ++facts.faces;
      // OpenMesh takes the next three lines as the corners, whatever they say.
      for (int k = 0; k < 3; ++k) {
        std::string_view corner;
        lines.next(corner);  // past the end: empty, and reported as missing below
        Tokens corner_tokens(corner);
        const std::string corner_at = "line " + std::to_string(lines.number());
        if (corner_tokens.next() != "vertex") fail(path, corner_at + ": expected 'vertex x y z' (file truncated?)");
        for (const char* axis : {"x", "y", "z"}) require_real(path, corner_tokens.next(), corner_at + ": vertex " + axis);
        ++facts.vertices;
      }
    } else if (keyword == "vertex") {
      fail(path, at + ": 'vertex' outside an 'outer loop'");
    }
  }
  return facts;
}

}  // namespace

MeshFileFacts check_mesh_file(const std::string& path, const std::string& format, std::string_view bytes) {
  if (bytes.empty()) fail(path, "file is empty");
  if (format == "obj") return check_obj(path, bytes);
  if (format == "off") return check_off(path, bytes);
  if (format == "ply") return check_ply(path, bytes);
  if (format == "stl") return check_stl(path, bytes);
  fail(path, "unknown mesh format '" + format + "'");
}

}  // namespace oit
