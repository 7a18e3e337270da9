// CheckRelationsConsistency against hand-made relations: exact loops close, a relation 3 cm or
// 0.5 deg off leaves that much in the loop it is part of, and duplicates count once.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "host_sim/eval/relations_consistency.hpp"

using dpcr::Pose2;
using dpcr::eval::Relation;

namespace {

// The relation between two poses of a made-up trajectory, stamped 1 s apart each.
Relation Between(const std::vector<Pose2>& poses, int a, int b) {
  return Relation{a * 1000000LL, b * 1000000LL, dpcr::Between(poses[static_cast<std::size_t>(a)], poses[static_cast<std::size_t>(b)])};
}

const std::vector<Pose2> kPoses = {Pose2{0.0f, 0.0f, 0.0f}, Pose2{1.0f, 0.2f, 0.3f}, Pose2{1.5f, 1.4f, 1.2f},
                                   Pose2{0.4f, 2.0f, 2.5f}};

}  // namespace

TEST_CASE("Relations taken from one trajectory close every loop") {
  std::vector<Relation> r = {Between(kPoses, 0, 1), Between(kPoses, 1, 2), Between(kPoses, 0, 2), Between(kPoses, 2, 3),
                             Between(kPoses, 1, 3)};
  const auto c = dpcr::eval::CheckRelationsConsistency(r);
  CHECK(c.loops == 2);  // 0-1-2 and 1-2-3
  CHECK(c.loop_trans_mean_m < 1e-5);
  CHECK(c.loop_rot_mean_deg < 1e-3);
  // The same relations given the other way round as well, and a scan related to itself: no new loop.
  r.push_back(Between(kPoses, 2, 0));
  r.push_back(Between(kPoses, 3, 3));
  CHECK(dpcr::eval::CheckRelationsConsistency(r).loops == 2);
}

TEST_CASE("A relation off by 3 cm or half a degree shows in its loop") {
  // Off along its own axis by 3 cm: the loop is left with 3 cm (turned into the loop's frame).
  Relation off = Between(kPoses, 0, 2);
  off.delta = off.delta * Pose2{0.03f, 0.0f, 0.0f};
  auto c = dpcr::eval::CheckRelationsConsistency({Between(kPoses, 0, 1), Between(kPoses, 1, 2), off});
  REQUIRE(c.loops == 1);
  CHECK(c.loop_trans_mean_m == Approx(0.03).margin(1e-5));
  CHECK(c.loop_rot_mean_deg < 1e-3);
  CHECK(c.relation_trans_rms_m == Approx(0.03 / std::sqrt(3.0)).margin(1e-5));
  // Off by half a degree about its end: the loop turns by as much.
  off = Between(kPoses, 0, 2);
  off.delta = off.delta * Pose2{0.0f, 0.0f, 0.5f * dpcr::kPi / 180.0f};
  c = dpcr::eval::CheckRelationsConsistency({Between(kPoses, 0, 1), Between(kPoses, 1, 2), off});
  REQUIRE(c.loops == 1);
  CHECK(c.loop_rot_mean_deg == Approx(0.5).margin(1e-3));
  CHECK(c.relation_rot_rms_deg == Approx(0.5 / std::sqrt(3.0)).margin(1e-3));
}

TEST_CASE("Relations without a loop of three say nothing") {
  const std::vector<Relation> r = {Between(kPoses, 0, 1), Between(kPoses, 1, 2), Between(kPoses, 2, 3)};
  const auto c = dpcr::eval::CheckRelationsConsistency(r);
  CHECK(c.loops == 0);
  CHECK(c.loop_trans_mean_m == 0.0);
}
