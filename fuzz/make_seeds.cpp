// Writes the generated seed inputs into DIR/<target>/: device bytes made by the encoders (the
// LD06 datasheet packet among them), a wheel-frame sequence, a tiny-profile map saved after a
// short synthetic run and the mapper targets' edit lists. The text formats' seeds are checked in
// (fuzz/seeds/).
// Usage: dpcr-fuzz-seeds DIR
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/mapper.hpp"
#include "fuzz/tiny_map_run.hpp"
#include "hal/ld06_decoder.hpp"
#include "hal/wheel_can_protocol.hpp"
#include "hal/xv11_decoder.hpp"
#include "tests/hal/golden_packets.hpp"

namespace {

using Bytes = std::vector<std::uint8_t>;

void Write(const std::filesystem::path& dir, const std::string& target, const std::string& name, const Bytes& bytes) {
  std::filesystem::create_directories(dir / target);
  std::ofstream out(dir / target / name, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// Two LD06 packets of one turn, with garbage between them.
Bytes Ld06Stream() {
  Bytes b(std::begin(dpcr_test::kLd06DatasheetPacket), std::end(dpcr_test::kLd06DatasheetPacket));
  b.insert(b.end(), {0x54, 0x00, 0x13});
  dpcr::Ld06Packet p;
  p.speed_deg_s = 3600;
  p.start_angle_cdeg = 35900;
  p.end_angle_cdeg = 200;  // wraps past 360
  p.timestamp_ms = 29990;
  for (int i = 0; i < dpcr::kLd06PointsPerPacket; ++i) p.points[i] = dpcr::Ld06Point{static_cast<std::uint16_t>(500 + 900 * i), 200};
  std::uint8_t packet[dpcr::kLd06PacketBytes];
  dpcr::EncodeLd06Packet(p, packet);
  b.insert(b.end(), packet, packet + sizeof(packet));
  return b;
}

Bytes Xv11Stream() {
  Bytes b(std::begin(dpcr_test::kXv11Packet), std::end(dpcr_test::kXv11Packet));
  dpcr::Xv11Packet p;
  p.index = dpcr::kXv11LastIndex;
  p.speed_rpm_x64 = 300 * 64;
  p.readings[0].distance_mm = 1234;
  p.readings[1].invalid = true;
  std::uint8_t packet[dpcr::kXv11PacketBytes];
  dpcr::EncodeXv11Packet(p, packet);
  b.insert(b.end(), packet, packet + sizeof(packet));
  return b;
}

void AppendFrame(Bytes* b, const dpcr::CanFrame& f) {
  for (int i = 0; i < 4; ++i) b->push_back(static_cast<std::uint8_t>(f.id >> (8 * i)));
  b->push_back(f.dlc);
  b->insert(b->end(), f.data, f.data + 8);
}

// Ticks, gyro and status frames with a counter rollover, a lost and a duplicated frame, a lift
// and a put-down, and a status frame with reserved flags set.
std::vector<dpcr::CanFrame> WheelFrames() {
  std::vector<dpcr::CanFrame> frames;
  for (int k = 0; k < 6; ++k) {
    dpcr::WheelTicksFrame t;
    t.left_ticks = static_cast<std::uint16_t>(65500 + 20 * k);
    t.right_ticks = static_cast<std::uint16_t>(100 + 25 * k);
    t.sequence = static_cast<std::uint8_t>(k == 4 ? 3 : k);
    t.time_10us = static_cast<std::uint32_t>((1 << 24) - 1500 + 1000 * k) & 0xFFFFFF;
    frames.push_back(dpcr::EncodeWheelFrame(t));
    dpcr::GyroFrame g;
    g.yaw_rate_mrad_s = static_cast<std::int16_t>(-50 * k);
    g.sequence = static_cast<std::uint8_t>(250 + k);
    g.time_10us = t.time_10us;
    frames.push_back(dpcr::EncodeGyroFrame(g));
    if (k == 1 || k == 3 || k == 5) {
      dpcr::StatusFrame status;
      status.flags = k == 1 ? dpcr::kStatusLiftedFlag : k == 5 ? 0x80 : 0;
      status.sequence = static_cast<std::uint8_t>(k);
      status.time_10us = t.time_10us;
      frames.push_back(dpcr::EncodeStatusFrame(status));
    }
  }
  return frames;
}

// The device pipeline's record form (fuzz_device_pipeline.cpp): lidar chunks and CAN frames.
Bytes PipelineStream(std::uint8_t mode, const Bytes& lidar) {
  Bytes b{mode};
  const std::vector<dpcr::CanFrame> frames = WheelFrames();
  std::size_t sent = 0, frame = 0;
  while (sent < lidar.size() || frame < frames.size()) {
    if (sent < lidar.size()) {
      const std::size_t n = lidar.size() - sent < 30 ? lidar.size() - sent : 30;
      b.insert(b.end(), {0, 2, static_cast<std::uint8_t>(n)});
      b.insert(b.end(), lidar.begin() + static_cast<std::ptrdiff_t>(sent), lidar.begin() + static_cast<std::ptrdiff_t>(sent + n));
      sent += n;
    }
    if (frame < frames.size()) {
      b.insert(b.end(), {1, 1});
      AppendFrame(&b, frames[frame++]);
    }
  }
  return b;
}

Bytes TinyMap() {
  static const dpcr::fuzz::TinyMapRun run;
  auto mapper = std::make_unique<dpcr::Mapper<dpcr::TinyProfile>>();
  if (mapper->Init(run.config) != dpcr::Status::kOk) return {};
  run.Feed(*mapper, 0, 30);
  struct Sink final : dpcr::MapByteSink {
    dpcr::Status Write(const std::uint8_t* data, std::size_t size) override {
      bytes.insert(bytes.end(), data, data + size);
      return dpcr::Status::kOk;
    }
    Bytes bytes;
  } sink;
  if (!mapper->SaveMap(sink).ok()) return {};
  return sink.bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const Bytes ld06 = Ld06Stream(), xv11 = Xv11Stream();
  Write(dir, "fuzz_ld06", "two_packets", [&] { Bytes b{46}; b.insert(b.end(), ld06.begin(), ld06.end()); return b; }());
  Write(dir, "fuzz_xv11", "two_packets", [&] { Bytes b{21}; b.insert(b.end(), xv11.begin(), xv11.end()); return b; }());
  Write(dir, "fuzz_device_pipeline", "ld06_arrival", PipelineStream(0, ld06));
  Write(dir, "fuzz_device_pipeline", "ld06_device_clock", PipelineStream(2, ld06));
  Write(dir, "fuzz_device_pipeline", "xv11", PipelineStream(1, xv11));
  Bytes wheels;
  for (const dpcr::CanFrame& f : WheelFrames()) AppendFrame(&wheels, f);
  Write(dir, "fuzz_wheel_can", "ticks_and_gyro", wheels);
  const Bytes map = TinyMap();
  if (map.empty()) {
    std::fprintf(stderr, "dpcr-fuzz-seeds: the tiny map could not be made\n");
    return 1;
  }
  Bytes as_is{0}, resealed{1};
  as_is.insert(as_is.end(), map.begin(), map.end());
  resealed.insert(resealed.end(), map.begin(), map.end());
  Write(dir, "fuzz_map_file", "tiny_map", as_is);
  Write(dir, "fuzz_map_file", "tiny_map_resealed", resealed);
  Write(dir, "fuzz_mapper_config", "defaults", Bytes{});
  Write(dir, "fuzz_mapper_config", "heading_jump", Bytes{0xB0});
  // Four scans with each kind of odometry, and a few edits of beams and stamps.
  // Head byte: bits 0-1 scans - 1, bits 2-3 scans per submap - 2, bits 4-5 the odometry.
  Write(dir, "fuzz_mapper_scans", "wheels", Bytes{0x07});
  Write(dir, "fuzz_mapper_scans", "wheels_two_scan_submaps", Bytes{0x03});
  Write(dir, "fuzz_mapper_scans", "wheels_and_gyro", Bytes{0x17});
  Write(dir, "fuzz_mapper_scans", "gyro_only", Bytes{0x27});
  Write(dir, "fuzz_mapper_scans", "lidar_only", Bytes{0x37});
  Write(dir, "fuzz_mapper_scans", "edited", Bytes{0x07, 0x17, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x24, 0x00});
  std::printf("seeds written to %s (map file %zu bytes)\n", dir.string().c_str(), map.size());
  return 0;
}
