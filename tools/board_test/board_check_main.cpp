// dpcr-board-check: compares the trajectory dpcr-firmware wrote inside the emulated board with
// the host replay's of the same streams (scans matched by stamp), and loads the map the
// firmware saved (map.yaml + the PGM it names). Prints one line of figures; exits 0 when every
// reference scan has a guest pose within the tolerances and the map loads.
//   dpcr-board-check --trajectory guest.tum --reference replay.tum --map-yaml map.yaml
//                    [--max-pos-m M] [--max-yaw-deg D] [--max-yaw-run N] [--reference-map replay/map.pgm]
//                    [--match stamp|relative]   (relative: times from each trajectory's first
//                    scan, nearest within 50 ms; for streams re-timed by the guest's clock)
// --max-yaw-run N: headings may differ by more than --max-yaw-deg on at most N consecutive scans
// (a transient in a fast spin, where two builds' registrations part for a scan or two and meet
// again); a longer stretch is a run that went another way. Default 0: no scan may.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "host_sim/eval/trajectory.hpp"

namespace {

struct Pgm {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> pixels;
};

// Binary PGM (P5, maxval 255), comments allowed in the header.
bool ReadPgm(const std::string& path, Pgm* out, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  std::string magic;
  in >> magic;
  auto next_int = [&in](int* v) {
    for (;;) {
      in >> std::ws;
      if (in.peek() == '#') {
        std::string comment;
        std::getline(in, comment);
        continue;
      }
      return static_cast<bool>(in >> *v);
    }
  };
  int maxval = 0;
  if (magic != "P5" || !next_int(&out->width) || !next_int(&out->height) || !next_int(&maxval) || maxval != 255 ||
      out->width <= 0 || out->height <= 0) {
    *error = path + ": not a P5 PGM of maxval 255";
    return false;
  }
  in.get();  // the one whitespace before the pixels
  out->pixels.resize(static_cast<std::size_t>(out->width) * static_cast<std::size_t>(out->height));
  if (!in.read(reinterpret_cast<char*>(out->pixels.data()), static_cast<std::streamsize>(out->pixels.size()))) {
    *error = path + ": truncated image";
    return false;
  }
  return true;
}

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

int main(int argc, char** argv) {
  std::string trajectory, reference, map_yaml, reference_map;
  double max_pos_m = 0.02;
  double max_yaw_deg = 1.0;
  long max_yaw_run = 0;
  std::string match = "stamp";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const char* v = argv[i + 1];
    if (a == "--trajectory") trajectory = v;
    else if (a == "--reference") reference = v;
    else if (a == "--map-yaml") map_yaml = v;
    else if (a == "--reference-map") reference_map = v;
    else if (a == "--match") match = v;
    else if (a == "--max-pos-m") max_pos_m = std::atof(v);
    else if (a == "--max-yaw-deg") max_yaw_deg = std::atof(v);
    else if (a == "--max-yaw-run") max_yaw_run = std::atol(v);
    else {
      std::fprintf(stderr, "dpcr-board-check: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (trajectory.empty() || reference.empty() || map_yaml.empty()) {
    std::fprintf(stderr, "usage: dpcr-board-check --trajectory T --reference R --map-yaml Y [...]\n");
    return 2;
  }
  std::vector<std::string> failures;
  dpcr::eval::Trajectory guest, host;
  try {
    guest = dpcr::eval::ReadTumFile(trajectory);
    host = dpcr::eval::ReadTumFile(reference);
  } catch (const std::exception& e) {
    std::printf("check: error: %s\n", e.what());
    return 1;
  }
  if (match == "relative" && !guest.empty() && !host.empty()) {
    // Each guest scan re-stamped to the reference's clock, then to the nearest reference stamp.
    const std::int64_t offset = host.front().stamp_us - guest.front().stamp_us;
    std::size_t j = 0;
    for (auto& p : guest) {
      const std::int64_t t = p.stamp_us + offset;
      while (j + 1 < host.size() && std::llabs(host[j + 1].stamp_us - t) <= std::llabs(host[j].stamp_us - t)) ++j;
      p.stamp_us = std::llabs(host[j].stamp_us - t) < 50000 ? host[j].stamp_us : -1;
    }
  }
  // Scans that share a stamp (two revolutions completed by one read) are paired in file order.
  std::map<std::int64_t, std::vector<dpcr::Pose2>> by_stamp;
  for (auto it = guest.rbegin(); it != guest.rend(); ++it) by_stamp[it->stamp_us].push_back(it->pose);
  long matched = 0;
  double pos_max = 0.0, pos_sum = 0.0, yaw_max = 0.0;
  long yaw_over = 0, yaw_run = 0, yaw_run_max = 0;  // scans over max_yaw_deg; consecutive ones
  for (const auto& p : host) {
    const auto found = by_stamp.find(p.stamp_us);
    if (found == by_stamp.end() || found->second.empty()) continue;
    const dpcr::Pose2 guest_pose = found->second.back();
    found->second.pop_back();
    ++matched;
    const double d = std::hypot(static_cast<double>(guest_pose.x - p.pose.x), static_cast<double>(guest_pose.y - p.pose.y));
    const double yaw = std::fabs(WrapAngle(static_cast<double>(guest_pose.theta - p.pose.theta))) * 180.0 / M_PI;
    pos_sum += d;
    pos_max = d > pos_max ? d : pos_max;
    yaw_max = yaw > yaw_max ? yaw : yaw_max;
    yaw_run = yaw > max_yaw_deg ? yaw_run + 1 : 0;
    yaw_over += yaw > max_yaw_deg;
    yaw_run_max = yaw_run > yaw_run_max ? yaw_run : yaw_run_max;
  }
  if (host.empty()) failures.push_back("empty reference trajectory");
  if (matched != static_cast<long>(host.size()) || matched != static_cast<long>(guest.size())) {
    failures.push_back("scans differ (guest " + std::to_string(guest.size()) + ", host " + std::to_string(host.size()) + ")");
  }
  if (pos_max > max_pos_m) failures.push_back("position difference over tolerance");
  if (yaw_run_max > max_yaw_run) failures.push_back("heading difference over tolerance");

  // The map: map.yaml names the image, its resolution and origin.
  std::ifstream yin(map_yaml);
  std::string image, line;
  double resolution = 0.0;
  while (std::getline(yin, line)) {
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (key == "image:") s >> image;
    if (key == "resolution:") s >> resolution;
  }
  Pgm pgm;
  std::string error;
  const std::string dir = map_yaml.substr(0, map_yaml.find_last_of('/') + 1);
  long occupied = 0, free_cells = 0, agree = 0, compared = 0;
  if (image.empty() || resolution <= 0.0) {
    failures.push_back(map_yaml + ": no image or resolution");
  } else if (!ReadPgm(image[0] == '/' ? image : dir + image, &pgm, &error)) {
    failures.push_back(error);
  } else {
    for (unsigned char c : pgm.pixels) {
      occupied += c < 100;
      free_cells += c > 200;
    }
    if (occupied == 0 || free_cells == 0) failures.push_back("map has no occupied or no free cells");
    Pgm ref;
    if (!reference_map.empty() && ReadPgm(reference_map, &ref, &error) && ref.width == pgm.width &&
        ref.height == pgm.height) {
      for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
        const int a = ref.pixels[i] < 100 ? 0 : ref.pixels[i] > 200 ? 2 : 1;
        const int b = pgm.pixels[i] < 100 ? 0 : pgm.pixels[i] > 200 ? 2 : 1;
        compared += 1;
        agree += a == b;
      }
    }
  }
  std::printf("check: scans=%ld/%zu pos_max_m=%.4f pos_mean_m=%.5f yaw_max_deg=%.3f yaw_over=%ld yaw_over_run=%ld "
              "map=%dx%d@%.3fm occupied=%ld free=%ld",
              matched, host.size(), pos_max, matched > 0 ? pos_sum / static_cast<double>(matched) : 0.0, yaw_max, yaw_over, yaw_run_max,
              pgm.width, pgm.height, resolution, occupied, free_cells);
  if (compared > 0) std::printf(" map_agreement=%.4f", static_cast<double>(agree) / static_cast<double>(compared));
  for (const std::string& f : failures) std::printf(" FAIL(%s)", f.c_str());
  std::printf("\n");
  return failures.empty() ? 0 : 1;
}
