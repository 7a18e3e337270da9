// World file parsers: the line-based text format (docs/world-format.md) and PGM floor plans.
#include <cmath>
#include <cstdint>
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
    {"door", 4, 4, "door <x1> <y1> <x2> <y2>"},
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
      const Door door{Vec2{num(1), num(2)}, Vec2{num(3), num(4)}};
      if (Norm(door.b - door.a) < 1e-6) Fail(source_name, line_no, "door has zero width");
      world.doors.push_back(door);
    } else if (key == "start") {
      world.start = Pose2d{num(1), num(2), WrapAngle(num(3))};
      world.has_start = true;
    }
  }
  if (world.segments.empty() && world.circles.empty()) Fail(source_name, line_no, "world has no walls or circles");
  if (world.rooms.empty()) {
    double x0, y0, x1, y1;
    world.Bounds(&x0, &y0, &x1, &y1);
    world.rooms.push_back(Room{"all", x0, y0, x1, y1});
  }
  CutDoors(&world);
  return world;
}

World ParsePgmWorld(const std::string& bytes, const std::string& source_name, double resolution_m,
                    Vec2 origin) {
  if (!(resolution_m > 0.0)) throw WorldError(source_name + ": PGM resolution must be positive");
  std::size_t pos = 0;
  // Header tokens, skipping whitespace and '#' comments.
  auto next_token = [&]() {
    for (;;) {
      while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
      if (pos < bytes.size() && bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
        continue;
      }
      break;
    }
    const std::size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    return bytes.substr(start, pos - start);
  };
  auto header_int = [&](const char* what) {
    const std::string tok = next_token();
    char* end = nullptr;
    const long v = std::strtol(tok.c_str(), &end, 10);
    if (tok.empty() || *end != '\0' || v <= 0 || v > 100000) {
      throw WorldError(source_name + ": bad PGM " + what + " '" + tok + "'");
    }
    return static_cast<int>(v);
  };
  const std::string magic = next_token();
  if (magic != "P5" && magic != "P2") throw WorldError(source_name + ": not a PGM file (magic '" + magic + "')");
  const int w = header_int("width");
  const int h = header_int("height");
  const int maxval = header_int("maxval");
  if (maxval > 65535) throw WorldError(source_name + ": bad PGM maxval");
  std::vector<std::uint8_t> dark(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  if (magic == "P5") {
    ++pos;  // the single whitespace after maxval
    const std::size_t bpp = maxval > 255 ? 2 : 1;
    if (bytes.size() < pos + dark.size() * bpp) throw WorldError(source_name + ": PGM pixel data truncated");
    for (std::size_t i = 0; i < dark.size(); ++i) {
      const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + pos + i * bpp);
      const int v = bpp == 2 ? (p[0] << 8 | p[1]) : p[0];
      dark[i] = 2 * v < maxval ? 1 : 0;
    }
  } else {
    for (std::size_t i = 0; i < dark.size(); ++i) {
      const std::string tok = next_token();
      if (tok.empty()) throw WorldError(source_name + ": PGM pixel data truncated");
      dark[i] = 2 * std::atoi(tok.c_str()) < maxval ? 1 : 0;
    }
  }
  auto is_dark = [&](int x, int row) {
    if (x < 0 || x >= w || row < 0 || row >= h) return false;
    return dark[static_cast<std::size_t>(row) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] != 0;
  };
  // World coordinates of pixel corner (x, row): row 0 is the top of the image (largest y).
  auto corner = [&](int x, int row) { return Vec2{origin.x + x * resolution_m, origin.y + (h - row) * resolution_m}; };
  World world;
  world.name = source_name;
  // Boundary edges between dark and light pixels, merged into maximal runs.
  for (int row = 0; row <= h; ++row) {  // horizontal edges on the line above pixel row `row`
    int run = -1;
    for (int x = 0; x <= w; ++x) {
      const bool edge = x < w && is_dark(x, row) != is_dark(x, row - 1);
      if (edge && run < 0) run = x;
      if (!edge && run >= 0) {
        world.segments.push_back(Segment{corner(run, row), corner(x, row), 0});
        run = -1;
      }
    }
  }
  for (int x = 0; x <= w; ++x) {  // vertical edges left of pixel column x
    int run = -1;
    for (int row = 0; row <= h; ++row) {
      const bool edge = row < h && is_dark(x, row) != is_dark(x - 1, row);
      if (edge && run < 0) run = row;
      if (!edge && run >= 0) {
        world.segments.push_back(Segment{corner(x, run), corner(x, row), 0});
        run = -1;
      }
    }
  }
  if (world.segments.empty()) throw WorldError(source_name + ": PGM has no dark (wall) pixels");
  world.rooms.push_back(Room{"all", origin.x, origin.y, origin.x + w * resolution_m, origin.y + h * resolution_m});
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
