// World file parsers: the line-based text format (docs/world-format.md) and PGM floor plans.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "host_sim/sim/world.hpp"

namespace dpcr::sim {
namespace {

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw WorldError(source + ":" + std::to_string(line) + ": " + what);
}

double ParseNumber(const std::string& token, const std::string& source, int line) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(token, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != token.size() || !std::isfinite(value)) Fail(source, line, "not a number: '" + token + "'");
  return value;
}

struct Keyword {
  const char* name;
  std::size_t min_args;
  std::size_t max_args;
  const char* usage;
};

constexpr Keyword kKeywords[] = {
    {"name", 1, 1, "name <world-name>"},
    {"material", 2, 2, "material <name> <return-probability 0..1>"},
    {"wall", 4, 5, "wall <x1> <y1> <x2> <y2> [material]"},
    {"box", 4, 5, "box <xmin> <ymin> <xmax> <ymax> [material]"},
    {"circle", 3, 4, "circle <x> <y> <radius> [material]"},
    {"room", 5, 5, "room <name> <xmin> <ymin> <xmax> <ymax>"},
    {"door", 4, 5, "door <x1> <y1> <x2> <y2> [leaf]"},
    {"start", 3, 3, "start <x> <y> <theta-rad>"},
};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw WorldError(path + ": cannot open world file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// PGM header tokens: whitespace and '#' comments skipped.
class PgmTokens {
 public:
  PgmTokens(const std::string& bytes, const std::string& source) : bytes_(bytes), source_(source) {}
  std::string Next() {
    for (;;) {
      while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
      if (pos_ < bytes_.size() && bytes_[pos_] == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    return bytes_.substr(start, pos_ - start);
  }
  int HeaderInt(const char* what) {
    const std::string tok = Next();
    char* end = nullptr;
    const long v = std::strtol(tok.c_str(), &end, 10);
    if (tok.empty() || *end != '\0' || v <= 0 || v > 100000) {
      throw WorldError(source_ + ": bad PGM " + what + " '" + tok + "'");
    }
    return static_cast<int>(v);
  }
  // Offset of the raster of a binary (P5) image: after the single whitespace that ends the header.
  std::size_t RasterStart() const { return pos_ + 1; }

 private:
  const std::string& bytes_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

// A floor-plan image reduced to what it says: which pixels are walls (darker than half the max).
struct DarkPixels {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> dark;  // row-major, row 0 at the top of the image
  bool At(int x, int row) const {
    if (x < 0 || x >= width || row < 0 || row >= height) return false;
    return dark[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] != 0;
  }
};

// P5 (8 or 16 bits) or P2; WorldError naming `source` on a bad header or truncated pixels.
DarkPixels ReadDarkPixels(const std::string& bytes, const std::string& source) {
  PgmTokens tokens(bytes, source);
  const std::string magic = tokens.Next();
  if (magic != "P5" && magic != "P2") throw WorldError(source + ": not a PGM file (magic '" + magic + "')");
  DarkPixels image;
  image.width = tokens.HeaderInt("width");
  image.height = tokens.HeaderInt("height");
  const int maxval = tokens.HeaderInt("maxval");
  if (maxval > 65535) throw WorldError(source + ": bad PGM maxval");
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  // Each pixel takes at least a byte of the file (P5: one or two, P2: a digit or a separator): a
  // header promising more than the file holds is refused before the raster is allocated.
  if (pixels > bytes.size()) throw WorldError(source + ": PGM pixel data truncated");
  image.dark.resize(pixels);
  if (magic == "P5") {
    const std::size_t start = tokens.RasterStart();
    const std::size_t bpp = maxval > 255 ? 2 : 1;
    if (bytes.size() < start + image.dark.size() * bpp) throw WorldError(source + ": PGM pixel data truncated");
    for (std::size_t i = 0; i < image.dark.size(); ++i) {
      const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + start + i * bpp);
      const int v = bpp == 2 ? (p[0] << 8 | p[1]) : p[0];
      image.dark[i] = 2 * v < maxval ? 1 : 0;
    }
  } else {
    for (std::size_t i = 0; i < image.dark.size(); ++i) {
      const std::string tok = tokens.Next();
      if (tok.empty()) throw WorldError(source + ": PGM pixel data truncated");
      char* end = nullptr;
      const long v = std::strtol(tok.c_str(), &end, 10);
      if (*end != '\0' || v < 0 || v > maxval) throw WorldError(source + ": bad PGM pixel '" + tok + "'");
      image.dark[i] = 2 * v < maxval ? 1 : 0;
    }
  }
  return image;
}

// Walls along the boundary edges between dark and light pixels, merged into maximal runs.
void AddBoundaryWalls(const DarkPixels& image, double resolution_m, Vec2 origin, World* world) {
  const int w = image.width, h = image.height;
  // World coordinates of pixel corner (x, row): row 0 is the top of the image (largest y).
  auto corner = [&](int x, int row) { return Vec2{origin.x + x * resolution_m, origin.y + (h - row) * resolution_m}; };
  for (int row = 0; row <= h; ++row) {  // horizontal edges on the line above pixel row `row`
    int run = -1;
    for (int x = 0; x <= w; ++x) {
      const bool edge = x < w && image.At(x, row) != image.At(x, row - 1);
      if (edge && run < 0) run = x;
      if (!edge && run >= 0) {
        world->segments.push_back(Segment{corner(run, row), corner(x, row), 0});
        run = -1;
      }
    }
  }
  for (int x = 0; x <= w; ++x) {  // vertical edges left of pixel column x
    int run = -1;
    for (int row = 0; row <= h; ++row) {
      const bool edge = row < h && image.At(x, row) != image.At(x - 1, row);
      if (edge && run < 0) run = row;
      if (!edge && run >= 0) {
        world->segments.push_back(Segment{corner(x, run), corner(x, row), 0});
        run = -1;
      }
    }
  }
}

// A world without rooms is one room, its bounds, for the coverage planner: it needs an area.
void AddWholeWorldRoom(World* world, const std::string& source, int line) {
  double x0, y0, x1, y1;
  world->Bounds(&x0, &y0, &x1, &y1);
  if (!(x0 < x1 && y0 < y1)) Fail(source, line, "world has no area (its walls lie on one line) and no room");
  world->rooms.push_back(Room{"all", x0, y0, x1, y1});
}

}  // namespace

World ParseWorldText(const std::string& text, const std::string& source_name) {
  World world;
  world.name = source_name;
  std::istringstream lines(text);
  std::string raw;
  int line_no = 0;
  while (std::getline(lines, raw)) {
    ++line_no;
    const std::size_t hash = raw.find('#');
    if (hash != std::string::npos) raw.resize(hash);
    std::istringstream tokens(raw);
    std::vector<std::string> t;
    for (std::string tok; tokens >> tok;) t.push_back(tok);
    if (t.empty()) continue;
    const Keyword* kw = nullptr;
    for (const Keyword& k : kKeywords) {
      if (t[0] == k.name) kw = &k;
    }
    if (kw == nullptr) Fail(source_name, line_no, "unknown keyword '" + t[0] + "'");
    const std::size_t args = t.size() - 1;
    if (args < kw->min_args || args > kw->max_args) {
      Fail(source_name, line_no, "expected '" + std::string(kw->usage) + "'");
    }
    auto num = [&](std::size_t i) { return ParseNumber(t[i], source_name, line_no); };
    auto material = [&](std::size_t i) {
      if (t.size() <= i) return 0;
      const int m = world.FindMaterial(t[i]);
      if (m < 0) Fail(source_name, line_no, "unknown material '" + t[i] + "' (declare it first)");
      return m;
    };
    const std::string& key = t[0];
    if (key == "name") {
      world.name = t[1];
    } else if (key == "material") {
      const double p = num(2);
      if (p < 0.0 || p > 1.0) Fail(source_name, line_no, "return probability must be in [0, 1]");
      world.SetMaterial(t[1], p);
    } else if (key == "wall") {
      const Vec2 a{num(1), num(2)};
      const Vec2 b{num(3), num(4)};
      if (Norm(b - a) < 1e-6) Fail(source_name, line_no, "wall has zero length");
      world.segments.push_back(Segment{a, b, material(5)});
    } else if (key == "box") {
      const double x0 = num(1), y0 = num(2), x1 = num(3), y1 = num(4);
      if (!(x0 < x1 && y0 < y1)) Fail(source_name, line_no, "box needs xmin < xmax and ymin < ymax");
      AddBox(&world, x0, y0, x1, y1, material(5));
    } else if (key == "circle") {
      const double r = num(3);
      if (r <= 0.0) Fail(source_name, line_no, "circle radius must be positive");
      world.circles.push_back(Circle{Vec2{num(1), num(2)}, r, material(4)});
    } else if (key == "room") {
      Room room{t[1], num(2), num(3), num(4), num(5)};
      if (!(room.xmin < room.xmax && room.ymin < room.ymax)) {
        Fail(source_name, line_no, "room needs xmin < xmax and ymin < ymax");
      }
      world.rooms.push_back(room);
    } else if (key == "door") {
      Door door{Vec2{num(1), num(2)}, Vec2{num(3), num(4)}};
      if (Norm(door.b - door.a) < 1e-6) Fail(source_name, line_no, "door has zero width");
      if (t.size() > 5) {
        if (t[5] != "leaf") Fail(source_name, line_no, "door takes only 'leaf' after its end points, not '" + t[5] + "'");
        door.leaf = true;
      }
      world.doors.push_back(door);
    } else if (key == "start") {
      world.start = Pose2d{num(1), num(2), WrapAngle(num(3))};
      world.has_start = true;
    }
  }
  if (world.segments.empty() && world.circles.empty()) Fail(source_name, line_no, "world has no walls or circles");
  if (world.rooms.empty()) AddWholeWorldRoom(&world, source_name, line_no);
  CheckWorldLimits(world, source_name);
  CutDoors(&world);
  // A door can span a whole wall: the simulator needs something left for the lidar to see.
  if (world.segments.empty() && world.circles.empty()) Fail(source_name, line_no, "the doors cut away every wall");
  return world;
}

World ParsePgmWorld(const std::string& bytes, const std::string& source_name, double resolution_m,
                    Vec2 origin) {
  if (!(resolution_m > 0.0)) throw WorldError(source_name + ": PGM resolution must be positive");
  const DarkPixels image = ReadDarkPixels(bytes, source_name);
  World world;
  world.name = source_name;
  world.rooms.push_back(Room{"all", origin.x, origin.y, origin.x + image.width * resolution_m,
                             origin.y + image.height * resolution_m});
  CheckWorldLimits(world, source_name);  // the image's footprint, before its edges are traced
  AddBoundaryWalls(image, resolution_m, origin, &world);
  if (world.segments.empty()) throw WorldError(source_name + ": PGM has no dark (wall) pixels");
  return world;
}

World LoadWorld(const std::string& name_or_path) {
  const bool builtin = std::filesystem::path(name_or_path).extension().empty() && !std::filesystem::exists(name_or_path);
  return builtin ? LoadBuiltinWorld(name_or_path) : LoadWorldFile(name_or_path);
}

World LoadWorldFile(const std::string& path) {
  const std::string bytes = ReadAll(path);
  if (!EndsWith(path, ".pgm")) return ParseWorldText(bytes, path);
  double resolution = 0.05;
  Vec2 origin;
  const std::string yaml_path = path.substr(0, path.size() - 4) + ".yaml";
  std::ifstream yaml(yaml_path);
  for (std::string line; yaml && std::getline(yaml, line);) {
    if (line.rfind("resolution:", 0) == 0) {
      resolution = std::atof(line.c_str() + 11);
    } else if (line.rfind("origin:", 0) == 0) {
      const std::size_t open = line.find('[');
      if (open != std::string::npos && std::sscanf(line.c_str() + open + 1, "%lf , %lf", &origin.x, &origin.y) != 2) {
        throw WorldError(yaml_path + ": cannot read origin");
      }
    }
  }
  return ParsePgmWorld(bytes, path, resolution, origin);
}

}  // namespace dpcr::sim
