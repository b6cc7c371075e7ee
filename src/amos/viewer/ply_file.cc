#include "amos/viewer/ply_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>

#include "amos/core/error.h"
#include "amos/core/whole_file.h"

namespace amos::viewer {
namespace {

enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::optional<Type> typeNamed(const std::string& name) {
  if (name == "char" || name == "int8") return Type::kInt8;
  if (name == "uchar" || name == "uint8") return Type::kUint8;
  if (name == "short" || name == "int16") return Type::kInt16;
  if (name == "ushort" || name == "uint16") return Type::kUint16;
  if (name == "int" || name == "int32") return Type::kInt32;
  if (name == "uint" || name == "uint32") return Type::kUint32;
  if (name == "float" || name == "float32") return Type::kFloat32;
  if (name == "double" || name == "float64") return Type::kFloat64;
  return std::nullopt;
}

std::size_t sizeOf(Type t) {
  switch (t) {
    case Type::kInt8: case Type::kUint8: return 1;
    case Type::kInt16: case Type::kUint16: return 2;
    case Type::kInt32: case Type::kUint32: case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 1;
}

bool isFloat(Type t) { return t == Type::kFloat32 || t == Type::kFloat64; }

struct Property {
  std::string name;
  Type type = Type::kFloat32;
  bool list = false;
  Type count_type = Type::kUint8;  // of a list
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  bool binary = false;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
};

// What a value of the body is for: the vertex's x y z / colour, a face's indices, nothing.
enum class Role { kX, kY, kZ, kRed, kGreen, kBlue, kIndices, kSkip };

Role roleOf(const std::string& element, const Property& p) {
  if (element == "vertex") {
    static const std::pair<const char*, Role> names[] = {{"x", Role::kX},     {"y", Role::kY},       {"z", Role::kZ},
                                                         {"red", Role::kRed}, {"green", Role::kGreen}, {"blue", Role::kBlue}};
    for (const auto& [name, role] : names)
      if (p.name == name && !p.list) return role;
  }
  if (element == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) return Role::kIndices;
  return Role::kSkip;
}

Header readHeader(const std::string& text, const std::string& file) {
  Header h;
  const std::size_t end = text.find("end_header");
  core::require(text.rfind("ply", 0) == 0 && end != std::string::npos,
                fmt::format("{}: not a PLY file (no 'ply' first line or no 'end_header')", file));
  const std::size_t line_end = text.find('\n', end);
  h.body_offset = line_end == std::string::npos ? text.size() : line_end + 1;
  std::istringstream lines(text.substr(0, end));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::istringstream words(line);
    std::string key;
    words >> key;
    const std::string where = fmt::format("{}: header line {}", file, number);
    if (key == "format") {
      std::string format;
      words >> format;
      core::require(format == "ascii" || format == "binary_little_endian",
                    fmt::format("{}: format '{}' is not supported (ascii or binary_little_endian)", where, format));
      h.binary = format != "ascii";
    } else if (key == "element") {
      Element e;
      long long count = -1;
      words >> e.name >> count;
      core::require(!e.name.empty() && count >= 0, fmt::format("{}: bad element line '{}'", where, line));
      e.count = static_cast<std::size_t>(count);
      h.elements.push_back(e);
    } else if (key == "property") {
      core::require(!h.elements.empty(), fmt::format("{}: a property before any element", where));
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type;
        words >> count_type >> type;
        const auto c = typeNamed(count_type);
        core::require(c.has_value(), fmt::format("{}: unknown type '{}'", where, count_type));
        p.list = true;
        p.count_type = *c;
      }
      const auto t = typeNamed(type);
      core::require(t.has_value(), fmt::format("{}: unknown type '{}'", where, type));
      p.type = *t;
      words >> p.name;
      h.elements.back().properties.push_back(p);
    }
  }
  return h;
}

// The fewest bytes one item of `e` takes in the body: in binary, its scalars and its lists' counts (a list may be
// empty); in ASCII, a character and a separator for each of those values.
std::size_t minimumItemBytes(const Element& e, bool binary) {
  std::size_t bytes = 0;
  for (const Property& p : e.properties) bytes += binary ? sizeOf(p.list ? p.count_type : p.type) : 2;
  return bytes;
}

// Refuses a header whose element counts claim more than the body holds, before anything of their size is
// allocated or looped over (the last ASCII value needs no separator: one byte of slack).
void requireCountsFitBody(const Header& h, std::size_t body_bytes, const std::string& file) {
  std::size_t left = body_bytes + (h.binary ? 0 : 1);
  for (const Element& e : h.elements) {
    const std::size_t item = minimumItemBytes(e, h.binary);
    if (item == 0) continue;  // no properties: nothing to read, whatever the count
    core::require(e.count <= left / item,
                  fmt::format("{}: element '{}' claims {} items of at least {} bytes, more than the {} bytes left "
                              "in the file hold",
                              file, e.name, e.count, item, left));
    left -= e.count * item;
  }
}

// The body's values one by one, binary or ASCII.
class BodyReader {
 public:
  BodyReader(const std::string& text, std::size_t offset, bool binary, std::string file)
      : text_(text), at_(offset), binary_(binary), file_(std::move(file)) {}

  double next(Type type) {
    return binary_ ? nextBinary(type) : nextAscii();
  }

  // The item count of list property `p` of item `item` of `element`: a whole number, and no more items than the
  // rest of the file can hold (so that a corrupt count fails at once, not after a loop over billions).
  std::size_t listCount(const Property& p, const std::string& element, std::size_t item) {
    const double n = next(p.count_type);
    const std::size_t left = text_.size() - at_;
    const std::size_t fit = binary_ ? left / sizeOf(p.type) : (left + 1) / 2;
    core::require(n >= 0 && n == std::floor(n) && n <= static_cast<double>(fit),
                  fmt::format("{}: {} {}: list '{}' claims {} items, more than the {} bytes left in the file hold",
                              file_, element, item, p.name, n, left));
    return static_cast<std::size_t>(n);
  }

 private:
  double nextBinary(Type type) {
    const std::size_t n = sizeOf(type);
    core::require(at_ + n <= text_.size(), fmt::format("{}: the file ends before its last element", file_));
    const char* p = text_.data() + at_;
    at_ += n;
    // Little-endian on disk; the machines this runs on are little-endian too (x86-64, arm64).
    switch (type) {
      case Type::kInt8: return static_cast<std::int8_t>(*p);
      case Type::kUint8: return static_cast<std::uint8_t>(*p);
      case Type::kInt16: return load<std::int16_t>(p);
      case Type::kUint16: return load<std::uint16_t>(p);
      case Type::kInt32: return load<std::int32_t>(p);
      case Type::kUint32: return load<std::uint32_t>(p);
      case Type::kFloat32: return load<float>(p);
      case Type::kFloat64: return load<double>(p);
    }
    return 0;
  }
  template <typename T>
  static double load(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return static_cast<double>(v);
  }
  double nextAscii() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    core::require(at_ < text_.size(), fmt::format("{}: the file ends before its last element", file_));
    const char* begin = text_.c_str() + at_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    core::require(end != begin, fmt::format("{}: '{}' is not a number", file_, std::string(begin, std::min<std::size_t>(20, std::strlen(begin)))));
    at_ += static_cast<std::size_t>(end - begin);
    return v;
  }

  const std::string& text_;
  std::size_t at_;
  bool binary_;
  std::string file_;
};

// A colour value as a byte: floats are 0..1, integers 0..255; out of range (NaN too) is clamped.
std::uint8_t colourByte(double v, Type type) {
  const double byte = isFloat(type) ? v * 255.0 : v;
  if (!(byte > 0)) return 0;
  return static_cast<std::uint8_t>(std::lround(std::min(byte, 255.0)));
}

// A vertex coordinate as a float: refused when it is not a finite number a float can hold (NaN, infinite, or a
// double beyond FLT_MAX), which the viewer could not place.
float coordinate(double v, const std::string& file, std::size_t vertex, Role role) {
  static const char* const kAxes[] = {"x", "y", "z"};
  core::require(std::isfinite(v) && std::abs(v) <= FLT_MAX,
                fmt::format("{}: vertex {} has {} = {}, not a finite coordinate", file, vertex,
                            kAxes[static_cast<int>(role) - static_cast<int>(Role::kX)], v));
  return static_cast<float>(v);
}

void readVertices(const Element& e, BodyReader& body, ColouredGeometry& g, const std::string& file) {
  std::vector<Role> roles;
  int found = 0;
  for (const Property& p : e.properties) {
    roles.push_back(roleOf(e.name, p));
    if (roles.back() == Role::kX || roles.back() == Role::kY || roles.back() == Role::kZ) ++found;
  }
  core::require(found == 3, fmt::format("{}: its vertices have no x y z", file));
  g.xyz.resize(3 * e.count);
  g.rgb.assign(3 * e.count, 200);  // light grey when the file has no colour
  for (std::size_t i = 0; i < e.count; ++i) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (p.list) {
        const std::size_t n = body.listCount(p, e.name, i);
        for (std::size_t j = 0; j < n; ++j) body.next(p.type);
        continue;
      }
      const double v = body.next(p.type);
      switch (roles[k]) {
        case Role::kX: case Role::kY: case Role::kZ:
          g.xyz[3 * i + static_cast<int>(roles[k]) - static_cast<int>(Role::kX)] = coordinate(v, file, i, roles[k]);
          break;
        case Role::kRed: case Role::kGreen: case Role::kBlue:
          g.rgb[3 * i + static_cast<int>(roles[k]) - static_cast<int>(Role::kRed)] = colourByte(v, p.type);
          break;
        default:
          break;
      }
    }
  }
}

void readFaces(const Element& e, BodyReader& body, ColouredGeometry& g, const std::string& file) {
  if (e.properties.empty()) return;
  const std::size_t vertices = g.vertexCount();
  std::vector<std::uint32_t> polygon;
  for (std::size_t i = 0; i < e.count; ++i) {
    for (const Property& p : e.properties) {
      if (!p.list) {
        body.next(p.type);
        continue;
      }
      const std::size_t n = body.listCount(p, e.name, i);
      polygon.clear();
      for (std::size_t j = 0; j < n; ++j) {
        const double index = body.next(p.type);
        core::require(index >= 0 && index < static_cast<double>(vertices),
                      fmt::format("{}: face {} names vertex {}, of {}", file, i, index, vertices));
        polygon.push_back(static_cast<std::uint32_t>(index));
      }
      if (roleOf(e.name, p) != Role::kIndices) continue;
      for (std::size_t j = 2; j < polygon.size(); ++j)  // a fan: polygons are convex in the files we read
        g.triangles.insert(g.triangles.end(), {polygon[0], polygon[j - 1], polygon[j]});
    }
  }
}

void skipElement(const Element& e, BodyReader& body) {
  if (e.properties.empty()) return;
  for (std::size_t i = 0; i < e.count; ++i)
    for (const Property& p : e.properties) {
      const std::size_t n = p.list ? body.listCount(p, e.name, i) : 1;
      for (std::size_t j = 0; j < n; ++j) body.next(p.type);
    }
}

}  // namespace

ColouredGeometry readPly(const std::filesystem::path& path) {
  const std::string file = path.string();
  core::require(std::filesystem::is_regular_file(path), fmt::format("{}: no such file", file));
  return parsePly(core::readWholeFile(path).value_or(std::string()), file);
}

ColouredGeometry parsePly(const std::string& text, const std::string& file) {
  const Header header = readHeader(text, file);
  requireCountsFitBody(header, text.size() - header.body_offset, file);
  BodyReader body(text, header.body_offset, header.binary, file);
  ColouredGeometry g;
  bool have_vertices = false;
  for (const Element& e : header.elements) {
    if (e.name == "vertex") {
      readVertices(e, body, g, file);
      have_vertices = true;
    } else if (e.name == "face") {
      core::require(have_vertices, fmt::format("{}: faces before the vertices", file));
      readFaces(e, body, g, file);
    } else {
      skipElement(e, body);
    }
  }
  core::require(have_vertices, fmt::format("{}: no vertex element", file));
  return g;
}

}  // namespace amos::viewer
