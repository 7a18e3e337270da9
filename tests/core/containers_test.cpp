// StaticVector and RingBuffer against std containers, and their full behaviour.
#include <catch2/catch.hpp>

#include <deque>
#include <random>
#include <vector>

#include "core/base/ring_buffer.hpp"
#include "core/base/static_vector.hpp"

using dpcr::Status;

TEST_CASE("StaticVector matches std::vector and rejects overflow") {
  dpcr::StaticVector<int, 8> v;
  std::vector<int> oracle;
  for (int i = 0; i < 8; ++i) {
    REQUIRE(v.push_back(i * 3) == Status::kOk);
    oracle.push_back(i * 3);
  }
  REQUIRE(v.full());
  REQUIRE(v.push_back(99) == Status::kCapacityExceeded);
  REQUIRE(v.size() == 8);
  REQUIRE(std::vector<int>(v.begin(), v.end()) == oracle);
  v.pop_back();
  REQUIRE(v.back() == 18);
  REQUIRE(v.resize(9) == Status::kCapacityExceeded);
  REQUIRE(v.resize(3) == Status::kOk);
  REQUIRE(v.size() == 3);
  REQUIRE(v.span().size() == 3);
}

TEST_CASE("RingBuffer keeps FIFO order like std::deque and rejects when full") {
  dpcr::RingBuffer<int, 5> ring;
  std::deque<int> oracle;
  std::mt19937 rng(7);
  for (int step = 0; step < 1000; ++step) {
    if (rng() % 3 != 0) {
      const int value = static_cast<int>(rng() % 1000);
      const Status s = ring.push_back(value);
      if (oracle.size() == 5) {
        REQUIRE(s == Status::kCapacityExceeded);
      } else {
        REQUIRE(s == Status::kOk);
        oracle.push_back(value);
      }
    } else if (!oracle.empty()) {
      ring.pop_front();
      oracle.pop_front();
    }
    REQUIRE(ring.size() == oracle.size());
    for (std::size_t i = 0; i < oracle.size(); ++i) REQUIRE(ring[i] == oracle[i]);
  }
}

TEST_CASE("RingBuffer emplace_back returns nullptr when full") {
  dpcr::RingBuffer<int, 2> ring;
  *ring.emplace_back() = 1;
  *ring.emplace_back() = 2;
  REQUIRE(ring.emplace_back() == nullptr);
  REQUIRE(ring.front() == 1);
  REQUIRE(ring.back() == 2);
}
