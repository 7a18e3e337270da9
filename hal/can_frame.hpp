// A classic CAN frame as the HAL sees it, independent of <linux/can.h>. The flag bits of
// `id` match Linux SocketCAN's can_id, so board/ copies struct can_frame fields unchanged.
#pragma once

#include <cstdint>

namespace dpcr {

constexpr std::uint32_t kCanEffFlag = 0x80000000u;  // 29-bit extended identifier
constexpr std::uint32_t kCanRtrFlag = 0x40000000u;  // remote transmission request
constexpr std::uint32_t kCanErrFlag = 0x20000000u;  // error frame (from the controller)
constexpr std::uint32_t kCanSffMask = 0x000007FFu;
constexpr std::uint32_t kCanEffMask = 0x1FFFFFFFu;

struct CanFrame {
  std::uint32_t id = 0;  // identifier | flags, as Linux can_id
  std::uint8_t dlc = 0;  // 0..8
  std::uint8_t data[8] = {};
};

}  // namespace dpcr
