#include "amos/viewer/ply_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>

#include "amos/core/error.h"
#include "amos/viewer/whole_file.h"

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

// The body's values one by one, binary or ASCII.
class BodyReader {
 public:
  BodyReader(const std::string& text, std::size_t offset, bool binary, std::string file)
      : text_(text), at_(offset), binary_(binary), file_(std::move(file)) {}

  double next(Type type) {
    return binary_ ? nextBinary(type) : nextAscii();
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

std::uint8_t colourByte(double v, Type type) {
  const double byte = isFloat(type) ? v * 255.0 : v;
  return static_cast<std::uint8_t>(std::clamp(std::lround(byte), 0L, 255L));
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
        const auto n = static_cast<std::size_t>(body.next(p.count_type));
        for (std::size_t j = 0; j < n; ++j) body.next(p.type);
        continue;
      }
      const double v = body.next(p.type);
      switch (roles[k]) {
        case Role::kX: case Role::kY: case Role::kZ:
          g.xyz[3 * i + static_cast<int>(roles[k]) - static_cast<int>(Role::kX)] = static_cast<float>(v);
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
  const std::size_t vertices = g.vertexCount();
  std::vector<std::uint32_t> polygon;
  for (std::size_t i = 0; i < e.count; ++i) {
    for (const Property& p : e.properties) {
      if (!p.list) {
        body.next(p.type);
        continue;
      }
      const auto n = static_cast<std::size_t>(body.next(p.count_type));
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
  for (std::size_t i = 0; i < e.count; ++i)
    for (const Property& p : e.properties) {
      const std::size_t n = p.list ? static_cast<std::size_t>(body.next(p.count_type)) : 1;
      for (std::size_t j = 0; j < n; ++j) body.next(p.type);
    }
}

}  // namespace

ColouredGeometry readPly(const std::filesystem::path& path) {
  const std::string file = path.string();
  core::require(std::filesystem::is_regular_file(path), fmt::format("{}: no such file", file));
  const std::string text = readWholeFile(path);
  const Header header = readHeader(text, file);
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
