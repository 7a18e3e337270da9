// The built-in worlds: the paper's validation hall, its three-room office (Table 1) and a
// ~100 m² apartment like its Figure 10 (Table 2). Coordinates in metres, x east, y north.
#include "host_sim/sim/world.hpp"

namespace dpcr::sim {
namespace {

constexpr double kLegRadius = 0.025;    // table leg
constexpr double kChairLeg = 0.015;     // chair leg
constexpr double kChairSide = 0.42;

void AddChair(World* w, double cx, double cy) { AddLegs(w, cx, cy, kChairSide, kChairSide, kChairLeg); }

// 10 m x 10 m: 1.5 m wide cross corridors, two workstation arrays, four partitioned offices.
World Hall() {
  World w;
  w.name = "hall";
  AddBox(&w, 0, 0, 10, 10);
  const double c0 = 4.25, c1 = 5.75;  // corridor edges
  AddWall(&w, 0, c0, c0, c0);
  AddWall(&w, c1, c0, 10, c0);
  AddWall(&w, 0, c1, c0, c1);
  AddWall(&w, c1, c1, 10, c1);
  AddWall(&w, c0, 0, c0, c0);
  AddWall(&w, c1, 0, c1, c0);
  AddWall(&w, c0, c1, c0, 10);
  AddWall(&w, c1, c1, c1, 10);
  AddWall(&w, 2.1, c1, 2.1, 10);   // north-west quadrant: two offices
  AddWall(&w, c1, 7.9, 10, 7.9);   // north-east quadrant: two offices
  w.doors = {{{2.0, c0}, {2.9, c0}}, {{7.0, c0}, {7.9, c0}}, {{0.6, c1}, {1.5, c1}}, {{2.8, c1}, {3.7, c1}},
             {{c1, 6.4}, {c1, 7.3}}, {{c1, 8.5}, {c1, 9.4}}};
  // Workstation arrays: back-to-back desks (panelled to the floor) with chair columns.
  for (double x0 : {0.7, 1.9, 5.0 + 1.4, 5.0 + 2.6}) {
    AddBox(&w, x0, 1.5, x0 + 1.2, 2.1);
    AddBox(&w, x0, 2.1, x0 + 1.2, 2.7);
    w.circles.push_back(Circle{{x0 + 0.6, 1.05}, 0.04, 0});
    w.circles.push_back(Circle{{x0 + 0.6, 3.15}, 0.04, 0});
  }
  AddLegs(&w, 8.0, 6.8, 1.6, 0.8, kLegRadius);  // meeting table
  AddBox(&w, 2.4, 9.4, 4.25, 10.0);             // shelf
  w.rooms = {{"corridor-h", 0, c0, 10, c1},     {"corridor-s", c0, 0, c1, c0}, {"corridor-n", c0, c1, c1, 10},
             {"workstations-w", 0, 0, c0, c0},  {"workstations-e", c1, 0, 10, c0},
             {"office-nw-a", 0, c1, 2.1, 10},   {"office-nw-b", 2.1, c1, c0, 10},
             {"office-ne-a", c1, c1, 10, 7.9},  {"office-ne-b", c1, 7.9, 10, 10}};
  w.has_start = true;
  w.start = Pose2d{5.0, 5.0, 0.0};
  CutDoors(&w);
  return w;
}

// 21 m x 5 m, three 7 m rooms in a row joined by doors, with tables, chairs and cabinets.
World Office() {
  World w;
  w.name = "office";
  AddBox(&w, 0, 0, 21, 5);
  AddWall(&w, 7, 0, 7, 5);
  AddWall(&w, 14, 0, 14, 5);
  w.doors = {{{7, 2.0}, {7, 2.9}, true}, {{14, 3.2}, {14, 4.1}, true}};  // both with a leaf (--doors)
  // Room 1: two desks with chairs, a filing cabinet.
  AddLegs(&w, 2.5, 1.2, 1.6, 0.8, kLegRadius);
  AddChair(&w, 2.5, 2.0);
  AddLegs(&w, 4.8, 3.7, 1.6, 0.8, kLegRadius);
  AddChair(&w, 4.8, 2.9);
  AddBox(&w, 0.0, 4.4, 1.2, 5.0);
  // Room 2: meeting table with six chairs.
  AddLegs(&w, 10.5, 2.5, 2.4, 1.2, kLegRadius);
  for (double x : {9.7, 10.5, 11.3}) {
    AddChair(&w, x, 1.5);
    AddChair(&w, x, 3.5);
  }
  AddBox(&w, 12.8, 0.0, 14.0, 0.5);
  // Room 3: desks along the north wall, boxes, a cabinet.
  AddBox(&w, 15.0, 4.3, 18.0, 5.0);
  AddChair(&w, 16.0, 3.8);
  AddChair(&w, 17.2, 3.8);
  AddBox(&w, 19.6, 0.0, 21.0, 0.6);
  AddBox(&w, 17.5, 1.2, 18.0, 1.7);
  w.circles.push_back(Circle{{20.3, 3.0}, 0.15, 0});  // waste bin
  w.rooms = {{"room-1", 0, 0, 7, 5}, {"room-2", 7, 0, 14, 5}, {"room-3", 14, 0, 21, 5}};
  w.has_start = true;
  w.start = Pose2d{1.0, 1.0, 0.0};
  CutDoors(&w);
  return w;
}

// ~100 m²: balcony (south), living room, kitchen, bathroom, hallway, two bedrooms.
World Apartment() {
  World w;
  w.name = "apartment";
  const int glass = w.SetMaterial("glass", 0.3);   // balcony railing glass: most beams pass through
  const int black = w.SetMaterial("black", 0.05);  // matte black cabinet: almost no returns
  // Outer outline: L shape, the balcony only in front of the living room.
  AddWall(&w, 0, 0, 6, 0, glass);
  AddWall(&w, 6, 0, 6, 1.4);
  AddWall(&w, 6, 1.4, 12, 1.4);
  AddWall(&w, 12, 1.4, 12, 9);
  AddWall(&w, 12, 9, 0, 9);
  AddWall(&w, 0, 9, 0, 0);
  // Inner walls.
  AddWall(&w, 0, 1.4, 6, 1.4);    // balcony / living
  AddWall(&w, 0, 6, 6, 6);        // living / kitchen + bathroom
  AddWall(&w, 3.5, 6, 3.5, 9);    // kitchen / bathroom
  AddWall(&w, 6, 1.4, 6, 9);      // living + bathroom / hallway
  AddWall(&w, 7.3, 1.4, 7.3, 9);  // hallway / bedrooms
  AddWall(&w, 7.3, 5, 12, 5);     // bedroom 1 / bedroom 2
  // The four room doors have a leaf (dpcr-sim --doors opens and closes them).
  w.doors = {{{2.0, 1.4}, {3.6, 1.4}, false},  // balcony sliding door
             {{1.0, 6.0}, {1.9, 6.0}, true},   // kitchen
             {{6.0, 3.4}, {6.0, 4.5}, false},  // living to hallway (an open arch)
             {{6.0, 7.0}, {6.0, 7.8}, true},   // bathroom
             {{7.3, 3.8}, {7.3, 4.6}, true},   // bedroom 1
             {{7.3, 6.5}, {7.3, 7.3}, true}};  // bedroom 2
  // Living room: TV cabinet, sofa, five-legged coffee table, armchair legs.
  AddBox(&w, 0.0, 2.8, 0.45, 4.6);
  AddBox(&w, 4.1, 2.4, 5.0, 5.0);
  AddLegs(&w, 2.4, 3.7, 1.2, 0.6, kLegRadius, /*centre_leg=*/true);
  AddLegs(&w, 3.0, 5.3, 0.6, 0.6, 0.03);
  // Balcony: the black floor cabinet, a plant pot.
  AddBox(&w, 4.6, 0.0, 5.8, 0.5, black);
  w.circles.push_back(Circle{{0.5, 0.5}, 0.2, 0});
  // Kitchen: counter along the west and north walls, dining table with four chairs.
  AddBox(&w, 0.0, 6.6, 0.6, 9.0);
  AddBox(&w, 0.6, 8.4, 3.5, 9.0);
  AddLegs(&w, 2.1, 7.3, 1.0, 0.7, kLegRadius);
  AddChair(&w, 1.75, 6.6);
  AddChair(&w, 2.45, 6.6);
  AddChair(&w, 1.75, 8.0);
  AddChair(&w, 2.45, 8.0);
  // Bathroom: shower tray, toilet, washbasin cabinet.
  AddBox(&w, 3.5, 8.0, 4.5, 9.0);
  AddBox(&w, 5.3, 8.3, 6.0, 9.0);
  AddBox(&w, 3.5, 6.0, 4.1, 6.9);
  // Hallway: shoe cabinet at the north end.
  AddBox(&w, 6.0, 8.6, 7.3, 9.0);
  // Bedroom 1: bed and wardrobe leaving a 0.45 m passage (the paper's narrow area, arrow A).
  AddBox(&w, 9.3, 1.4, 10.95, 3.4);
  AddBox(&w, 11.4, 1.4, 12.0, 5.0);
  AddLegs(&w, 8.0, 2.0, 0.45, 0.45, 0.02);  // bedside stool
  // Bedroom 2: bed, wardrobe, desk with a chair.
  AddBox(&w, 9.8, 6.6, 12.0, 8.2);
  AddBox(&w, 7.3, 8.4, 9.3, 9.0);
  AddLegs(&w, 8.2, 5.4, 1.2, 0.6, kLegRadius);
  AddChair(&w, 8.2, 6.0);
  w.rooms = {{"balcony", 0, 0, 6, 1.4},     {"living", 0, 1.4, 6, 6},     {"kitchen", 0, 6, 3.5, 9},
             {"bathroom", 3.5, 6, 6, 9},    {"hallway", 6, 1.4, 7.3, 9},  {"bedroom-1", 7.3, 1.4, 12, 5},
             {"bedroom-2", 7.3, 5, 12, 9}};
  w.has_start = true;
  w.start = Pose2d{3.0, 2.0, 0.0};
  CutDoors(&w);
  return w;
}

}  // namespace

std::vector<std::string> BuiltinWorldNames() { return {"hall", "office", "apartment"}; }

World LoadBuiltinWorld(const std::string& name) {
  if (name == "hall") return Hall();
  if (name == "office") return Office();
  if (name == "apartment") return Apartment();
  throw WorldError("unknown built-in world '" + name + "' (hall, office, apartment)");
}

}  // namespace dpcr::sim
