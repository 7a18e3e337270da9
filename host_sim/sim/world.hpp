// A simulated floor as data: wall segments and circles (table/chair legs), each with a material
// whose return probability models black or glass surfaces, rooms (the coverage planner's units),
// doors (openings cut into walls) and a start pose. Built-in worlds and the file formats
// (docs/world-format.md) all produce this.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "host_sim/sim/geometry.hpp"

namespace dpcr::sim {

struct Material {
  std::string name;
  double return_probability = 1.0;  // chance that a beam hitting this surface gives a return
};

struct Segment {
  Vec2 a;
  Vec2 b;
  int material = 0;  // index into World::materials
};

struct Circle {
  Vec2 centre;
  double radius_m = 0.0;
  int material = 0;
};

struct Room {
  std::string name;
  double xmin = 0.0;
  double ymin = 0.0;
  double xmax = 0.0;
  double ymax = 0.0;
  bool Contains(Vec2 p) const { return p.x >= xmin && p.x <= xmax && p.y >= ymin && p.y <= ymax; }
};

// An opening: the part of any wall lying along [a, b] is removed by CutDoors(). With a leaf, a
// door closes it now and then (host_sim/sim/doors.hpp, dpcr-sim --doors).
struct Door {
  Vec2 a;
  Vec2 b;
  bool leaf = false;
};

// Thrown for malformed world files and unknown world names; what() starts with "file:line:".
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct World {
  std::string name;
  std::vector<Material> materials{Material{"default", 1.0}};
  std::vector<Segment> segments;
  std::vector<Circle> circles;
  std::vector<Room> rooms;
  std::vector<Door> doors;
  bool has_start = false;
  Pose2d start;

  // Index of the named material, or -1.
  int FindMaterial(const std::string& material_name) const;
  // Adds (or redefines) a material and returns its index.
  int SetMaterial(const std::string& material_name, double return_probability);
  // Axis-aligned bounds of all geometry and rooms.
  void Bounds(double* xmin, double* ymin, double* xmax, double* ymax) const;
};

// Builders used by the built-in worlds and the parsers.
void AddWall(World* world, double x1, double y1, double x2, double y2, int material = 0);
// A closed rectangle outline (cabinet, bed, box).
void AddBox(World* world, double xmin, double ymin, double xmax, double ymax, int material = 0);
// Four legs at the corners of a w x h footprint centred at (cx, cy), inset by the leg radius,
// plus a centre leg when asked (the apartment's five-legged coffee table).
void AddLegs(World* world, double cx, double cy, double w, double h, double leg_radius_m,
             bool centre_leg = false, int material = 0);
// Removes from every wall the part collinear with (within 1 cm of) and overlapping a door.
void CutDoors(World* world);

// What a loaded world may span. A vacuum's floor fits in far less; beyond this the simulator's
// set-up grows with the area (a 500 m box: 20 s and 100 MB before the first scan, a 5 km one
// never started), and coordinates far from the origin lose the mapper's float precision.
inline constexpr double kMaxWorldExtentM = 200.0;     // width and height of the bounds
inline constexpr double kMaxWorldCoordinateM = 1000.0;  // |x|, |y| of every point, start included
// WorldError naming `source` when the world's bounds or start break those limits.
void CheckWorldLimits(const World& world, const std::string& source);

// "hall", "office" or "apartment"; WorldError for any other name.
World LoadBuiltinWorld(const std::string& name);
std::vector<std::string> BuiltinWorldNames();

// Text world (any extension but .pgm) or PGM floor plan (.pgm; resolution and origin from a
// ROS map_server .yaml beside it when present, else 0.05 m and (0, 0)). WorldError on failure.
World LoadWorldFile(const std::string& path);
// What the apps' --world takes: a built-in name (no extension and no such file), else a file.
World LoadWorld(const std::string& name_or_path);
// Parses a text world; `source_name` prefixes error messages.
World ParseWorldText(const std::string& text, const std::string& source_name);
// PGM (P2 or P5) floor plan: pixels darker than half the max value are walls.
World ParsePgmWorld(const std::string& bytes, const std::string& source_name, double resolution_m,
                    Vec2 origin);

}  // namespace dpcr::sim
